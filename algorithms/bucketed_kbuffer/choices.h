#pragma once
// The bucketed k-buffer's choice parameters besides the transfer functions
// (transfer_functions.h), declared once for its descriptor (register.cpp)
// and the technique (bucketed_kbuffer.cpp).
#include "base/params.h"

namespace oit::bkb {

// buckets: the neighbour query in one hashed bucket (on), over all fragments
// (off), in each pixel's whole list as its one bucket (single: one-object
// scenes), or single on a one-object scene and on elsewhere (automatic,
// resolved before the run).
enum class BucketMode { automatic, on, off, single };
inline const Choices<BucketMode> kBucketModes{{BucketMode::automatic, "auto"},
                                              {BucketMode::on, "on"},
                                              {BucketMode::off, "off"},
                                              {BucketMode::single, "single"}};

// neighbor_search: walk the two sorted lists (merge) or scan the bucket or
// list that `buckets` selects (bucket).
enum class NeighborSearch { merge, bucket };
inline const Choices<NeighborSearch> kNeighborSearches{{NeighborSearch::merge, "merge"},
                                                       {NeighborSearch::bucket, "bucket"}};

// slot_layout: Z, B, colour, normal and a features word (kappa + found mask)
// per slot, stylized in a pass of its own (full), or murray2016's 128 bits
// without the features word, stylized in the neighbour pass (paper).
enum class SlotLayout { full, paper };
inline const Choices<SlotLayout> kSlotLayouts{{SlotLayout::full, "full"}, {SlotLayout::paper, "paper"}};

// depth_bits: the depth's share of the 32-bit key; the shape id gets the rest.
inline const Choices<int> kDepthBits{{16, "16"}, {24, "24"}};

}  // namespace oit::bkb
