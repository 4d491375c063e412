#version 450 core
// Stencil shadow volumes: the volume's faces only count in the stencil buffer;
// nothing to compute per fragment. The GL state the draws need (colour and
// depth writes off, the stencil operations of depth-fail or depth-pass, depth
// clamp or an infinite far plane, the scene's polygon offset) is in
// shadow_volume.vert's header.
void main() {}
