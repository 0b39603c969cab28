// What the techniques' per-pixel storage shares: where a pixel's data lies
// in pixel-major buffers, and the unsigned order of view depths that their
// sort keys use.

// Index of the pixel this fragment shades in buffers of one entry (or one
// run of entries) per pixel, row by row, of a frame `width` pixels wide.
uint oit_pixel_index(int width) { return uint(gl_FragCoord.y) * uint(width) + uint(gl_FragCoord.x); }

// The bits of a float view depth mapped to unsigned order: IEEE floats
// compare like sign-magnitude integers, so negative depths (behind the eye)
// are flipped and sort first, as in the reference.
uint oit_depth_order(uint bits) { return (bits & 0x80000000u) != 0u ? ~bits : bits | 0x80000000u; }
