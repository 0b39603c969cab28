#include "harness/output/flip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace oit {
namespace {

constexpr double kPi = 3.14159265358979323846;
// The paper's constants (section 4).
constexpr double kQc = 0.7, kPc = 0.4, kPt = 0.95, kQf = 0.5, kFeatureWidth = 0.082;

using Vec3 = std::array<double, 3>;

// Linear sRGB to CIE XYZ and back: the matrix derived from IEC 61966-2-1's
// primaries (x, y) R 0.64 0.33, G 0.30 0.60, B 0.15 0.06 and D65 white
// 0.3127 0.3290, and its exact inverse (10 digits). The 7-digit table often
// quoted (0.4124564 ...) assumes a slightly different white and moved the
// mean FLIP of the reference-implementation cases (flip.h) by up to 9e-5.
constexpr double kToXyz[3][3] = {{0.4123907993, 0.3575843394, 0.1804807884},
                                 {0.2126390059, 0.7151686788, 0.0721923154},
                                 {0.0193308187, 0.1191947798, 0.9505321522}};
constexpr double kToRgb[3][3] = {{3.2409699419, -1.5373831776, -0.4986107603},
                                 {-0.9692436363, 1.8759675015, 0.0415550574},
                                 {0.0556300797, -0.2039769589, 1.0569715142}};

Vec3 multiply(const double (&m)[3][3], const Vec3& v) {
  return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
          m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

// The reference white: linear RGB (1, 1, 1) in XYZ, so white is exactly L* 100.
const Vec3& white() {
  static const Vec3 w = multiply(kToXyz, {1.0, 1.0, 1.0});
  return w;
}

Vec3 xyz_to_ycxcz(const Vec3& xyz) {
  const double x = xyz[0] / white()[0], y = xyz[1] / white()[1], z = xyz[2] / white()[2];
  return {116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)};
}

Vec3 ycxcz_to_xyz(const Vec3& o) {
  const double y = (o[0] + 16.0) / 116.0;
  return {(o[1] / 500.0 + y) * white()[0], y * white()[1], (y - o[2] / 200.0) * white()[2]};
}

// CIELAB of linear RGB, then the Hunt adjustment (a and b scaled by L/100).
Vec3 hunt_lab(const Vec3& rgb) {
  const Vec3 xyz = multiply(kToXyz, rgb);
  auto f = [](double t) {
    constexpr double delta = 6.0 / 29.0;
    return t > delta * delta * delta ? std::cbrt(t) : t / (3.0 * delta * delta) + 4.0 / 29.0;
  };
  const double fx = f(xyz[0] / white()[0]), fy = f(xyz[1] / white()[1]), fz = f(xyz[2] / white()[2]);
  const double l = 116.0 * fy - 16.0;
  return {l, 0.01 * l * 500.0 * (fx - fy), 0.01 * l * 200.0 * (fy - fz)};
}

double hyab(const Vec3& a, const Vec3& b) {
  const double da = a[1] - b[1], db = a[2] - b[2];
  return std::abs(a[0] - b[0]) + std::sqrt(da * da + db * db);
}

struct Plane {
  int width = 0, height = 0;
  std::vector<double> v;
  double& at(int x, int y) { return v[size_t(y) * size_t(width) + size_t(x)]; }
  double at(int x, int y) const { return v[size_t(y) * size_t(width) + size_t(x)]; }
};

// `in` correlated with kernel_x along rows, then kernel_y along columns
// (both centred, odd length), borders replicated. Rows are padded once and
// columns summed row by row, so the inner loops run over contiguous memory.
Plane separable(const Plane& in, const std::vector<double>& kernel_x, const std::vector<double>& kernel_y) {
  const int w = in.width, h = in.height;
  const int rx = int(kernel_x.size() / 2), ry = int(kernel_y.size() / 2);
  Plane rows{w, h, std::vector<double>(in.v.size())}, out{w, h, std::vector<double>(in.v.size(), 0.0)};
  std::vector<double> padded(size_t(w + 2 * rx));
  for (int y = 0; y < h; ++y) {
    const double* source = &in.v[size_t(y) * size_t(w)];
    for (int x = -rx; x < w + rx; ++x) padded[size_t(x + rx)] = source[std::clamp(x, 0, w - 1)];
    double* target = &rows.v[size_t(y) * size_t(w)];
    for (int x = 0; x < w; ++x) {
      double sum = 0.0;
      for (size_t i = 0; i < kernel_x.size(); ++i) sum += kernel_x[i] * padded[size_t(x) + i];
      target[x] = sum;
    }
  }
  for (int y = 0; y < h; ++y) {
    double* target = &out.v[size_t(y) * size_t(w)];
    for (int i = -ry; i <= ry; ++i) {
      const double k = kernel_y[size_t(i + ry)];
      const double* source = &rows.v[size_t(std::clamp(y + i, 0, h - 1)) * size_t(w)];
      for (int x = 0; x < w; ++x) target[x] += k * source[x];
    }
  }
  return out;
}

// The contrast sensitivity filter of one opponent channel (paper Table 1):
// a1 sqrt(pi/b1) exp(-pi^2 r^2/b1) + a2 sqrt(pi/b2) exp(-pi^2 r^2/b2), r in
// degrees, normalised to sum 1 over the square the widest of the three
// spans (3 standard deviations). Each term is a product of 1D Gaussians,
// so the 2D filter is two separable passes.
Plane csf_filter(const Plane& in, double a1, double b1, double a2, double b2, double ppd) {
  const int radius = int(std::ceil(3.0 * std::sqrt(0.04 / (2.0 * kPi * kPi)) * ppd));
  auto gaussian = [&](double b) {
    std::vector<double> g(size_t(2 * radius + 1));
    for (int i = -radius; i <= radius; ++i) g[size_t(i + radius)] = std::exp(-kPi * kPi * (i / ppd) * (i / ppd) / b);
    return g;
  };
  const std::vector<double> g1 = gaussian(b1), g2 = gaussian(b2);
  const double c1 = a1 * std::sqrt(kPi / b1), c2 = a2 * std::sqrt(kPi / b2);
  const double s1 = std::accumulate(g1.begin(), g1.end(), 0.0), s2 = std::accumulate(g2.begin(), g2.end(), 0.0);
  const double total = c1 * s1 * s1 + c2 * s2 * s2;
  Plane out = separable(in, g1, g1);
  for (double& v : out.v) v *= c1 / total;
  if (c2 != 0.0) {
    const Plane second = separable(in, g2, g2);
    for (size_t i = 0; i < out.v.size(); ++i) out.v[i] += second.v[i] * c2 / total;
  }
  return out;
}

// The colour pipeline up to the Hunt-adjusted CIELAB of each pixel.
std::vector<Vec3> perceived_colours(const Image& image, double ppd) {
  const size_t pixels = size_t(image.width) * size_t(image.height);
  Plane channel[3];
  for (Plane& p : channel) p = {image.width, image.height, std::vector<double>(pixels)};
  for (size_t i = 0; i < pixels; ++i) {
    Vec3 rgb;
    for (int c = 0; c < 3; ++c) {
      const float v = image.rgba[4 * i + size_t(c)];
      rgb[size_t(c)] = std::isfinite(v) ? std::clamp(double(v), 0.0, 1.0) : 0.0;
    }
    const Vec3 o = xyz_to_ycxcz(multiply(kToXyz, rgb));
    for (int c = 0; c < 3; ++c) channel[c].v[i] = o[size_t(c)];
  }
  // b2 = 1e-5 where a2 = 0 only avoids a division by zero in the paper's formula.
  const Plane a = csf_filter(channel[0], 1.0, 0.0047, 0.0, 1e-5, ppd);
  const Plane rg = csf_filter(channel[1], 1.0, 0.0053, 0.0, 1e-5, ppd);
  const Plane by = csf_filter(channel[2], 34.1, 0.04, 13.5, 0.025, ppd);
  std::vector<Vec3> lab(pixels);
  for (size_t i = 0; i < pixels; ++i) {
    Vec3 rgb = multiply(kToRgb, ycxcz_to_xyz({a.v[i], rg.v[i], by.v[i]}));
    for (double& c : rgb) c = std::clamp(c, 0.0, 1.0);
    lab[i] = hunt_lab(rgb);
  }
  return lab;
}

// The edge (first derivative of a Gaussian) and point (second derivative)
// detectors along x, positive weights normalised to sum 1 and negative to
// -1; the Gaussian across, normalised to sum 1. The 2D filters are their
// products, so normalising the factors normalises the 2D filter alike.
struct FeatureKernels {
  std::vector<double> gaussian, edge, point;
};

FeatureKernels feature_kernels(double ppd) {
  const double sd = 0.5 * kFeatureWidth * ppd;
  const int radius = int(std::ceil(3.0 * sd));
  FeatureKernels k;
  for (int i = -radius; i <= radius; ++i) {
    const double g = std::exp(-double(i * i) / (2.0 * sd * sd));
    k.gaussian.push_back(g);
    k.edge.push_back(-double(i) * g);
    k.point.push_back((double(i * i) / (sd * sd) - 1.0) * g);
  }
  const double sum = std::accumulate(k.gaussian.begin(), k.gaussian.end(), 0.0);
  for (double& g : k.gaussian) g /= sum;
  for (std::vector<double>* d : {&k.edge, &k.point}) {
    double positive = 0.0, negative = 0.0;
    for (double w : *d) (w > 0.0 ? positive : negative) += w;
    for (double& w : *d) w = w > 0.0 ? w / positive : w / -negative;
  }
  return k;
}

// Per pixel: the magnitudes of the edge and the point response of the
// luminance (Y / Y_white).
struct Features {
  std::vector<double> edge, point;
};

Features features(const Image& image, const FeatureKernels& k) {
  const size_t pixels = size_t(image.width) * size_t(image.height);
  Plane y{image.width, image.height, std::vector<double>(pixels)};
  for (size_t i = 0; i < pixels; ++i) {
    Vec3 rgb;
    for (int c = 0; c < 3; ++c) {
      const float v = image.rgba[4 * i + size_t(c)];
      rgb[size_t(c)] = std::isfinite(v) ? std::clamp(double(v), 0.0, 1.0) : 0.0;
    }
    y.v[i] = multiply(kToXyz, rgb)[1] / white()[1];
  }
  const Plane ex = separable(y, k.edge, k.gaussian), ey = separable(y, k.gaussian, k.edge);
  const Plane px = separable(y, k.point, k.gaussian), py = separable(y, k.gaussian, k.point);
  Features f{std::vector<double>(pixels), std::vector<double>(pixels)};
  for (size_t i = 0; i < pixels; ++i) {
    f.edge[i] = std::sqrt(ex.v[i] * ex.v[i] + ey.v[i] * ey.v[i]);
    f.point[i] = std::sqrt(px.v[i] * px.v[i] + py.v[i] * py.v[i]);
  }
  return f;
}

}  // namespace

std::vector<float> flip_map(const Image& test, const Image& reference, double pixels_per_degree) {
  if (test.width != reference.width || test.height != reference.height)
    throw std::invalid_argument("FLIP: a " + std::to_string(test.width) + "x" + std::to_string(test.height) +
                                " image against a " + std::to_string(reference.width) + "x" +
                                std::to_string(reference.height) + " reference");
  const std::vector<Vec3> lab_test = perceived_colours(test, pixels_per_degree);
  const std::vector<Vec3> lab_reference = perceived_colours(reference, pixels_per_degree);
  const FeatureKernels kernels = feature_kernels(pixels_per_degree);
  const Features f_test = features(test, kernels), f_reference = features(reference, kernels);
  // The largest colour distance: pure green against pure blue.
  const double cmax = std::pow(hyab(hunt_lab({0.0, 1.0, 0.0}), hunt_lab({0.0, 0.0, 1.0})), kQc);
  const double knee = kPc * cmax;
  std::vector<float> error(lab_test.size());
  for (size_t i = 0; i < error.size(); ++i) {
    const double distance = std::pow(hyab(lab_test[i], lab_reference[i]), kQc);
    const double colour =
        distance < knee ? kPt / knee * distance : kPt + (distance - knee) / (cmax - knee) * (1.0 - kPt);
    const double feature_difference = std::max(std::abs(f_test.edge[i] - f_reference.edge[i]),
                                               std::abs(f_test.point[i] - f_reference.point[i]));
    const double feature = std::pow(feature_difference / std::sqrt(2.0), kQf);
    error[i] = float(std::pow(colour, 1.0 - feature));
  }
  return error;
}

double mean_flip(const Image& test, const Image& reference, double pixels_per_degree) {
  const std::vector<float> error = flip_map(test, reference, pixels_per_degree);
  double sum = 0.0;
  for (float e : error) sum += e;
  return error.empty() ? 0.0 : sum / double(error.size());
}

}  // namespace oit
