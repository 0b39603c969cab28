#pragma once
// LDR-FLIP (Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström and
// Fairchild 2020, "FLIP: A Difference Evaluator for Alternating Images",
// Proc. ACM Comput. Graph. Interact. Tech. 3(2), 15), written from the
// paper: a per-pixel error in [0, 1] that approximates what a viewer sees
// when flipping between the two images.
//  - colour: both images to the opponent space YCxCz, each channel filtered
//    with its contrast sensitivity function (the paper's Gaussians,
//    Table 1), back to linear RGB (clamped), to CIELAB with the Hunt
//    adjustment (a, b scaled by L/100), HyAB distance ^ qc = 0.7, remapped
//    so that pc = 0.4 of the largest distance (green vs blue) maps to
//    pt = 0.95;
//  - features: edges (first Gaussian derivative) and points (second) of the
//    luminance, sigma = 0.082 / 2 degrees, difference ^ qf = 0.5;
//  - error = colour ^ (1 - feature).
// Viewing condition: the paper's default, 0.7 m from a 0.7 m wide 3840
// pixel screen (67 pixels per degree). Analytic values: identical images
// 0; uniform green vs uniform blue 1 (the normalising pair); uniform black
// vs white 0.95 + 0.05 (100^qc - pc cmax) / ((1 - pc) cmax) ~ 0.9674.
// Checked against NVIDIA's reference implementation (NVlabs/flip,
// cpp/FLIP.h, commit 00ac8f5b) run outside this repository on image pairs
// the test regenerates (tests/image_output_test.cpp, Flip.MatchesNvidias*):
// means within 2.1e-5 relative, pixels within 1.1e-4 (the reference works
// in float, and its RGB-XYZ matrix differs from IEC 61966-2-1's in the
// fifth digit). None of its code is here: this is written from the paper.
#include <vector>

#include "harness/output/image.h"

namespace oit {

inline constexpr double kFlipPixelsPerDegree = 0.7 * 3840.0 / 0.7 * 3.14159265358979323846 / 180.0;

// Per-pixel FLIP of `test` against `reference` (RGB of linear images, as
// composited, clamped to [0, 1]; alpha is not part of what is seen), rows
// as in Image. Throws when the sizes differ.
std::vector<float> flip_map(const Image& test, const Image& reference,
                            double pixels_per_degree = kFlipPixelsPerDegree);
// Its mean, the single number the authors recommend (0 for empty images).
double mean_flip(const Image& test, const Image& reference, double pixels_per_degree = kFlipPixelsPerDegree);

}  // namespace oit
