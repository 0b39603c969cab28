#version 450 core
// Triangle-index neighbour search (pastyrik2016 Algorithm 3,
// neighbors=triangle_index): for every sorted fragment and each of the 4
// adjacent pixels (left = x-1, right = x+1, down = y-1, up = y+1, GL window
// coordinates), the first (nearest) fragment of the adjacent list whose
// triangle shares a vertex index with the fragment's own (the sort stored
// the triangle's vertex indices in each record's geometry, sort.comp).
//
// One invocation per pixel (per covered pixel with storage=linearized:
// pixel_dispatch.glsl), not per fragment: the pixel's fragments are
// taken IB_GROUP (at most four) at a time, their vertex indices held in
// registers, and each adjacent list is read once per group, every candidate
// tested against the group's; a group stops reading a list when all of its
// fragments found theirs. Each
// fragment still gets the first match in list order, so the links are those
// of a scan per fragment. On llvmpipe the SIMD lanes are then neighbouring
// pixels, and each gather of candidates serves four tests per lane, where a
// dispatch per fragment ran consecutive fragments of one pixel in the lanes,
// all gathering the same candidate to test it once. Four, not eight: as fast
// on deep lists and no slower than the dispatch per fragment on short ones,
// where eight unrolls tests for fragments a short list does not have
// (README, Neighbour search).
#include "algorithms/illustration_buffer/ib_storage.glsl"
#include "algorithms/illustration_buffer/views.glsl"
#include "algorithms/illustration_buffer/pixel_dispatch.glsl"

// IB_GROUP (the host's define): 4, or 1 or 2 for frames whose lists are
// all that short (neighbor_stage.cpp, NeighborStage::triangle_search).

// This group's fragments (their triangles' vertex indices) and their links.
uvec3 mine[IB_GROUP];
uvec4 links[IB_GROUP];

bool shares_vertex(uvec3 a, uvec3 b) {
  // At least one shared vertex index: a neighbour (rules 2-4 of section 3.4).
  return any(equal(a, b.xxx)) || any(equal(a, b.yyy)) || any(equal(a, b.zzz));
}

// links[i][d] := the first fragment of `other`'s list that shares a vertex
// with mine[i], for the group's fragments in `pending` (a bit each); the
// others keep IB_NONE.
void scan(uint other, int d, uint pending) {
  const uint end = ib_pixel_first(other) + ib_pixel_count(other);
  for (uint b = ib_pixel_first(other); b < end && pending != 0u; ++b) {
    const uvec3 theirs = ib_sorted_geometry(b).xyz;
    for (int i = 0; i < IB_GROUP; ++i) {
      if ((pending & (1u << i)) != 0u && shares_vertex(mine[i], theirs)) {
        links[i][d] = b;
        pending &= ~(1u << i);
      }
    }
  }
}

// Direction d towards the adjacent pixel (x, y); IB_OFF_IMAGE outside the image.
void search(int x, int y, int d, uint pending) {
  if (x < 0 || y < 0 || x >= ib.width || y >= ib.height) {
    for (int i = 0; i < IB_GROUP; ++i) links[i][d] = IB_OFF_IMAGE;
    return;
  }
  scan(uint(y) * uint(ib.width) + uint(x), d, pending);
}

void main() {
  uint pixel;
  if (!ib_invocation_pixel(pixel)) return;
  const int x = int(pixel % uint(ib.width)), y = int(pixel / uint(ib.width));
  const uint first = ib_pixel_first(pixel), count = ib_pixel_count(pixel);
  for (uint group = first; group < first + count; group += uint(IB_GROUP)) {
    const uint size = min(first + count - group, uint(IB_GROUP));
    for (int i = 0; i < IB_GROUP; ++i) {
      mine[i] = ib_sorted_geometry(group + min(uint(i), size - 1u)).xyz;  // past the list: a copy, never written
      links[i] = uvec4(IB_NONE);
    }
    const uint pending = (1u << size) - 1u;
    search(x - 1, y, 0, pending);
    search(x + 1, y, 1, pending);
    search(x, y - 1, 2, pending);
    search(x, y + 1, 3, pending);
    for (int i = 0; i < IB_GROUP; ++i)
      if (uint(i) < size) ib_shade[group + uint(i)].links = links[i];
  }
}
