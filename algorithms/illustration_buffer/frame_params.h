#pragma once
// The illustration buffer's parameters as its shaders read them: one
// uniform buffer of IbFrameParams (bindings.h) per technique, written by
// upload() before the frame's fill (again where an overflow makes the fill
// run again with a larger pool) and once more with the fill's outcome (the
// stored fragments and the covered pixels the later passes read); and the
// IbPassParams of every pass that differs from its neighbours (a sweep's
// direction, a listed diffusion step's number), uploaded once, each bound
// at its own range for its pass.
#include <cstdint>

#include "algorithms/illustration_buffer/bindings.h"
#include "algorithms/illustration_buffer/settings.h"
#include "harness/gl/handles.h"
#include "harness/gl/uniform_block.h"

namespace oit::illustration_buffer {

class FrameParams : public UniformBlock<IbFrameParams> {
 public:
  // The settings' parameters in `values`; `steps`: the diffusion steps whose
  // pass records are needed (Settings::iterations).
  FrameParams(const Settings& settings, uint32_t steps);
  // The sweep in direction `index` (0-3: stylize_stage.cpp, kSweepDirections).
  void bind_sweep(uint32_t index) const { bind_pass(index); }
  // The listed diffusion step `step` (1 .. steps).
  void bind_step(uint32_t step) const { bind_pass(kSweeps + step); }

  static constexpr uint32_t kSweeps = 4;
  static constexpr int kSweepDirections[kSweeps][2] = {{1, 1}, {-1, -1}, {1, -1}, {-1, 1}};

 private:
  void bind_pass(uint32_t index) const;
  Buffer passes_;
  GLsizeiptr pass_stride_ = 0;
};

}  // namespace oit::illustration_buffer
