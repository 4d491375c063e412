#version 450 core
// Depth-only pass: no colour output; the bias is glPolygonOffset's slope-scaled one.
void main() {}
