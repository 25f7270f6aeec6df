// One pass of a tree sum (shared_step.h, GB_TREE_PASS_LEVELS): each workgroup sums the 2^levels values from
// gl_WorkGroupID.x 2^levels on into one, by the pairwise tree of treeSum (cpu-reference/stages/stages.cpp), which it
// equals to the bit: every block starts at a multiple of 2^levels, where the levels' pairs start too. Each of `lanes`
// invocations (a power of two) first sums a run of 2^levels / lanes consecutive values alone, then the workgroup
// joins the runs' sums pairwise through shared memory, a level between two barriers: on a GPU one value an
// invocation and eight shared levels, on a CPU driver's 64 invocations four values each and six.

shared float treePartial[gl_WorkGroupSize.x];

float treeCombined(float a, float b, bool largest) { return largest ? max(a, b) : a + b; }

// The invocations that hold a run: the largest power of two within the workgroup and the block.
uint treeLanes() { return 1u << findMSB(min(gl_WorkGroupSize.x, 1u << GB_TREE_PASS_LEVELS)); }
uint treeRun() { return (1u << GB_TREE_PASS_LEVELS) / treeLanes(); }
uint treeBlockFirst() { return gl_WorkGroupID.x << GB_TREE_PASS_LEVELS; }
// The values of this workgroup's block among n.
uint treeBlockCount(uint n) { return min(n, treeBlockFirst() + (1u << GB_TREE_PASS_LEVELS)) - treeBlockFirst(); }

// Into `result`, the tree of VALUE(i) over this invocation's run of the block of n values: a binary counter of partial
// sums, partial[l] the sum of the last complete run of 2^l values, joined to its right neighbour as soon as that
// completes; the runs left at the end join from the smallest up, as the levels carry an odd last value.
#define GB_TREE_RUN(result, n, VALUE, largest)                                                                        \
  {                                                                                                                   \
    float partial_[GB_TREE_PASS_LEVELS + 1u];                                                                         \
    const uint from_ = treeBlockFirst() + gl_LocalInvocationID.x * treeRun();                                         \
    const uint count_ = gl_LocalInvocationID.x < treeLanes() && from_ < (n) ? min(n, from_ + treeRun()) - from_ : 0u; \
    for (uint i_ = 0u; i_ < count_; ++i_) {                                                                           \
      float v_ = VALUE(from_ + i_);                                                                                   \
      uint l_ = 0u;                                                                                                   \
      for (; (i_ & (1u << l_)) != 0u; ++l_) v_ = treeCombined(partial_[l_], v_, largest);                             \
      partial_[l_] = v_;                                                                                              \
    }                                                                                                                 \
    bool have_ = false;                                                                                               \
    for (uint l_ = 0u; l_ <= GB_TREE_PASS_LEVELS; ++l_)                                                               \
      if ((count_ & (1u << l_)) != 0u) {                                                                              \
        result = have_ ? treeCombined(partial_[l_], result, largest) : partial_[l_];                                  \
        have_ = true;                                                                                                 \
      }                                                                                                               \
  }

// The workgroup's sum: each invocation's run sum `mine` (anything where it has no run) joined level by level, the
// pairs (2k, 2k + 1) as in treeSum. Every invocation of the workgroup calls it (it has barriers) and gets the sum.
float treeOfRuns(float mine, uint n, bool largest) {
  const uint t = gl_LocalInvocationID.x;
  barrier();  // the shared array's last use is over
  if (t < treeLanes()) treePartial[t] = mine;
  for (uint m = (treeBlockCount(n) + treeRun() - 1u) / treeRun(); m > 1u; m = (m + 1u) / 2u) {
    barrier();
    float v = 0.0;
    const bool joins = t < (m + 1u) / 2u;
    if (joins)
      v = 2u * t + 1u < m ? treeCombined(treePartial[2u * t], treePartial[2u * t + 1u], largest) : treePartial[2u * t];
    barrier();
    if (joins) treePartial[t] = v;
  }
  barrier();
  return treePartial[0];
}
