// sort=static_arrays (sort.comp, IB_STATIC_ARRAYS): pastyrik2016 section
// 3.2, "Sorting in Array of Fixed Size", with the three arrays of 64
// entries its section 4.1 times against the dynamic sort (its Fig. 7): the
// list is loaded into local arrays of IB_STATIC_ENTRIES whatever the
// frame's lists, selection-sorted there (the variant the paper timed) and
// copied out nearest first. Unlike sort=array the arrays are not sized to
// the frame's longest list.
//
// The arrays hold, per entry: the fill record (the paper's IDs), the depth
// order bits (its depths), and the stable triangle id, the tie-break of the
// depth order that every sort here shares (README, Sort); the paper's third
// array holds the distances between layers instead, the input of its eq. 1,
// which modulation=ray_distance computes in the compose from the sorted
// depths. The memory is the paper's: 3 x 64 x 4 B per invocation.
//
// Selection sort swaps, so two entries of equal (depth, triangle) may leave
// list order; such entries are one triangle at one pixel twice, with the
// same colour and depth, so no image changes (sort=array keeps them in
// list order).

bool static_entry_precedes(uint depth_a, uint triangle_a, uint depth_b, uint triangle_b) {
  return depth_a < depth_b || (depth_a == depth_b && triangle_a < triangle_b);
}

void sort_static_arrays(uint start, uint length, uint pixel) {
  uint ids[IB_STATIC_ENTRIES], depths[IB_STATIC_ENTRIES], triangles[IB_STATIC_ENTRIES];
  const uint loaded = min(length, IB_STATIC_ENTRIES);
  uint node = start;
  for (uint k = 0u; k < loaded; ++k) {
    const uvec4 taken = sort_key(node);
    depths[k] = taken.x;
    triangles[k] = taken.y;
    ids[k] = taken.z;
    node = IB_FOLLOW(node, taken);
  }
#ifdef IB_TRUNCATES
  // A list longer than the arrays (compiled for frames with one): each
  // further fragment replaces the farthest entry when nearer, so the arrays
  // keep the IB_STATIC_ENTRIES nearest. One flat loop (sort.comp: no list
  // walk nests a loop): each iteration takes the next fragment, or scans one
  // entry for the farthest and, after the last, replaces it.
  uint taken_count = loaded, scan = IB_STATIC_ENTRIES, farthest = 0u;
  uvec3 pending = uvec3(0u);
  while (taken_count < length || scan < IB_STATIC_ENTRIES) {
    if (scan == IB_STATIC_ENTRIES) {
      const uvec4 taken = sort_key(node);
      pending = taken.xyz;
      node = IB_FOLLOW(node, taken);
      ++taken_count;
      farthest = 0u;
      scan = 1u;
    } else {
      if (!static_entry_precedes(depths[scan], triangles[scan], depths[farthest], triangles[farthest])) farthest = scan;
      if (++scan == IB_STATIC_ENTRIES &&
          static_entry_precedes(pending.x, pending.y, depths[farthest], triangles[farthest])) {
        depths[farthest] = pending.x;
        triangles[farthest] = pending.y;
        ids[farthest] = pending.z;
      }
    }
  }
#endif
  // Selection sort of the first `kept` positions: each takes the nearest
  // of the entries not yet placed (max_per_pixel <= IB_STATIC_ENTRIES, host).
  const uint kept = min(loaded, ib.max_per_pixel);
  const uint first = sorted_range(pixel, kept);
  for (uint i = 0u; i < kept; ++i) {
    uint nearest = i;
    for (uint j = i + 1u; j < loaded; ++j)
      if (static_entry_precedes(depths[j], triangles[j], depths[nearest], triangles[nearest])) nearest = j;
    const uint depth = depths[nearest], triangle = triangles[nearest], id = ids[nearest];
    depths[nearest] = depths[i];
    triangles[nearest] = triangles[i];
    ids[nearest] = ids[i];
    depths[i] = depth;
    triangles[i] = triangle;
    ids[i] = id;
    copy_record(first + i, id, pixel);
  }
}
