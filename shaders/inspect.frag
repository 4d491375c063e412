#version 450 core
// Inspection overlay: one flat colour per kind of element.
uniform vec4 u_colour;
layout(location = 0) out vec4 o_color;
void main() { o_color = u_colour; }
