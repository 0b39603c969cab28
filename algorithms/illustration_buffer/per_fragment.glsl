// Per-fragment compute passes run one invocation per record of fragData2;
// the dispatch is two-dimensional when the groups exceed 65535 in x.
layout(local_size_x = 64) in;

uint ib_fragment_index() {
  return (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u + gl_LocalInvocationID.x;
}

