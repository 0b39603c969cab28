// Shared by C++ and GLSL: attribute locations, uniform locations and buffer
// binding points that the harness sets up for every technique. Techniques
// use bindings >= OIT_FIRST_TECHNIQUE_BINDING for their own buffers.
#ifndef OIT_SHADERS_BINDINGS_H
#define OIT_SHADERS_BINDINGS_H

#define OIT_ATTRIB_POSITION 0
#define OIT_ATTRIB_NORMAL 1
#define OIT_ATTRIB_COLOR 2
#define OIT_ATTRIB_OBJECT_ID 3
#define OIT_ATTRIB_SURFACE_ID 4
#define OIT_ATTRIB_UV 5
#define OIT_ATTRIB_MEAN_CURVATURE 6

// Uniforms of the shared geometry vertex shader / shading function.
#define OIT_UNIFORM_VIEW 0
#define OIT_UNIFORM_PROJECTION 1
#define OIT_UNIFORM_LIT 2
#define OIT_UNIFORM_BACKGROUND 3
// ivec2: where the frame's pixel (0, 0) lies in the whole image (a screen tile's offset; 0 untiled).
#define OIT_UNIFORM_PIXEL_ORIGIN 4
// Locations from here on are free for techniques.
#define OIT_FIRST_TECHNIQUE_UNIFORM 8

// SSBO with the stable id of every submitted triangle (indexed by gl_PrimitiveID).
#define OIT_BINDING_TRIANGLE_IDS 0
#define OIT_FIRST_TECHNIQUE_BINDING 1

#endif
