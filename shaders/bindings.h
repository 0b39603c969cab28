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

// Storage buffer binding points from here on are the techniques' (0 is
// kept for the harness; nothing uses it since the triangle ids moved to a
// buffer texture).
#define OIT_FIRST_TECHNIQUE_BINDING 1

// Texture unit of the stable id of every submitted triangle, an R32UI buffer
// texture indexed by gl_PrimitiveID (shading.glsl). A buffer texture, not an
// SSBO: on llvmpipe a texelFetch at a per-fragment address is a vector
// gather, an SSBO load a loop over the lanes (the l-LFB's fill on 32 quads
// at 256x256: 11.2 against 12.5 ms, 13 alternated rounds). The last of the
// 16 units every GL 4.5 fragment stage has: techniques use the units below.
#define OIT_UNIT_TRIANGLE_IDS 15

#endif
