#version 450 core
// Lookup of techniques that decide shadow outside the shading pass (stencil
// shadow volumes: only fragments with a zero stencil count are shaded lit).
float shadow_visibility(vec3 world, vec3 normal) { return 1.0; }
