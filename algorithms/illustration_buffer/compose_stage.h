#pragma once
// The compose (stage "compose", carnecky2013 section 4.6): each pixel's
// sorted range blended front to back into the frame's target, with the
// opacity of the fragment's own alpha, of its fields (modulated modes; from
// the sweeps' distances on a swept frame) or of the fill's purely local
// opacity.
#include "algorithms/illustration_buffer/frame_plan.h"
#include "algorithms/illustration_buffer/settings.h"
#include "harness/toolkit/technique.h"

namespace oit::illustration_buffer {

class ComposeStage {
 public:
  explicit ComposeStage(const Settings& settings);
  // With the sorted views and the stylize result bound.
  void run(const Frame& frame, const FramePlan& plan) const;

 private:
  Program compose_, swept_;  // swept_: the swept frames' (may_sweep)
};

}  // namespace oit::illustration_buffer
