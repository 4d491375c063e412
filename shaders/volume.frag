#version 450 core
// Stencil shadow volumes: the volume's faces only count in the stencil buffer
// (colour and depth writes are off); nothing to compute per fragment.
void main() {}
