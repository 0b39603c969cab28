#pragma once
// What one frame of the illustration buffer does, decided once at the start
// of render() (FramePlan) and never changed during the frame; and what the
// fill found (FillResult), which the later stages take as it is. The sort's
// array, and with sort=auto on linked lists whether it sorts dynamically,
// follow from the fill's longest list (SortStage::choose).
#include <cstdint>

namespace oit::illustration_buffer {

// Where the fill puts the records: per-pixel linked lists, exact ranges
// after a counting pass, or per-pixel arrays of the slots the last frame
// sized (Settings::Storage).
enum class FillStorage { linked, linearized, arrays };

struct FramePlan {
  // arrays: with storage=arrays_when_even a list longer than the slots
  // sends the frame to exact ranges, which FillResult::storage says.
  FillStorage storage = FillStorage::linked;
  bool flat_records = false;  // the fill stores no colour (Settings::flat_color_records)
  bool modulated = false;     // neighbour search and stylize run (Settings::diffused)
  bool swept = false;         // the diffusion sweeps to the fixed point (Diffusion)
  bool tracked = false;       // the diffusion's steps run over worklists (skip_converged)
  bool alpha_seeds = false;   // ... which also start where a neighbour's alpha differs
  int tile = 0;               // the screen tile (0 untiled)
  int tiles = 1;
};

struct FillResult {
  FillStorage storage = FillStorage::linked;  // as planned, or linearized after an arrays overflow
  uint32_t longest = 0;                        // the longest list
  uint64_t produced = 0, stored = 0, dropped = 0, truncated_lists = 0;
  uint64_t passes = 0;  // geometry passes (a counting pass, a retry)
  bool arrays() const { return storage == FillStorage::arrays; }
  bool linearized() const { return storage == FillStorage::linearized; }
};

}  // namespace oit::illustration_buffer
