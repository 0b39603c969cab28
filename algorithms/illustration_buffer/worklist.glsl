// Worklists of the diffusion that skips converged fragments (skip_converged;
// README, Diffusion). A fragment's next
// value depends only on its own fields and on its links, and links reach
// only the 4 adjacent pixels; so when a fragment of pixel p changes, only
// fragments of p and of its 4 adjacent pixels can change in the next step.
// The step that sees a change queues those pixels for the next step; every
// other fragment would compute exactly the value it has.
//
// A worklist starts with its indirect-dispatch arguments (x: one group, and
// one more per 64 entries beyond the first 64, at most 65535; the shader
// strides over the rest; an empty list still runs its one group, which
// empties the list after next)
// and its count, then the queued pixel indices. ib_stamp[p] is the last
// step p was queued for, so a pixel enters a list once. (A list per step
// keeps the dispatches small: on llvmpipe every workgroup has a fixed cost,
// so one workgroup per tile that checks a mark was slower than the full pass.)
layout(std430, binding = IB_STAMPS_BINDING) coherent buffer IbStamps { uint ib_stamp[]; };
layout(std430, binding = IB_WORK_OUT_BINDING) coherent buffer IbWorkOut {
  uint ib_out_groups_x, ib_out_groups_y, ib_out_groups_z, ib_out_count;
  uint ib_work_out[];
};
// Fragment updates computed per pixel (one invocation per pixel and step: a
// plain add), summed on the host for the counters.
layout(std430, binding = IB_PIXEL_UPDATES_BINDING) buffer IbPixelUpdates { uint ib_pixel_updates[]; };
// The step the pixels queued now are for (2 = the second diffusion step).

// Appends pixel q to the list being filled (one more group per 64 entries).
void ib_append(uint q) {
  const uint at = atomicAdd(ib_out_count, 1u);
  if (at % 64u == 0u && at > 0u && at / 64u < 65535u) atomicAdd(ib_out_groups_x, 1u);
  ib_work_out[at] = q;
}

void ib_enqueue(int x, int y) {
  if (x < 0 || y < 0 || x >= ib.width || y >= ib.height) return;
  const uint q = uint(y) * uint(ib.width) + uint(x);
  // A plain read first: most queued pixels are seen by several fragments.
  if (ib_stamp[q] >= ib_pass.next_step || atomicMax(ib_stamp[q], ib_pass.next_step) >= ib_pass.next_step) return;
  ib_append(q);
}

// Queues `pixel` and its 4 adjacent pixels for step ib_pass.next_step.
void ib_enqueue_around(uint pixel) {
  const int x = int(pixel % uint(ib.width)), y = int(pixel / uint(ib.width));
  ib_enqueue(x, y);
  ib_enqueue(x - 1, y);
  ib_enqueue(x + 1, y);
  ib_enqueue(x, y - 1);
  ib_enqueue(x, y + 1);
}
