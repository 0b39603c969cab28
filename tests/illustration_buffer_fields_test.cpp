// illustration_buffer's transparency fields (carnecky2013 sections 5.2-5.5)
// against a CPU model on two overlapping screen-aligned quads: the
// boundary conditions, beta and gamma spread by eq. 9 or eq. 8
// (field_diffusion), the profiles of eq. 10 and 11 and the compositing of
// Algorithm 3, every value in float as the shaders compute it; and what
// field_diffusion=homogeneous cannot run with (the sweeps), and that its
// default leaves the images of every other parameter set as they were.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "harness/output/image.h"
#include "scenes/random_scenes.h"
#include "tests/gl_fixture.h"

namespace oit {
namespace {

// Two quads of alpha 0.3 that overlap in part, each partly off the other
// (silhouettes, and halos where one passes over the other's inside).
const RawParams kTwoQuads = {{"count", "2"}, {"size", "0.35"}, {"seed", "12"}};
constexpr int kSide = 64;
constexpr float kAlpha = 0.3f;

// What the model runs: the paper's section 5.4 choices.
struct FieldModel {
  bool homogeneous = false;  // eq. 8 (field_diffusion=homogeneous), else eq. 9
  int iterations = 20;
  float lambda_beta = 0.05f, lambda_gamma = 0.1f;
  std::string profile = "none";  // none, exponential (eq. 10), power (eq. 11)
  float p = 1.0f;
};

RawParams technique_params(const FieldModel& m, const std::string& search) {
  std::ostringstream lb, lg, p;
  lb << m.lambda_beta;
  lg << m.lambda_gamma;
  p << m.p;
  RawParams params = {{"neighbors", search},
                      {"modulation", "silhouette_halo"},
                      {"field_diffusion", m.homogeneous ? "homogeneous" : "nonphysical"},
                      {"iterations", std::to_string(m.iterations)},
                      {"lambda_beta", lb.str()},
                      {"lambda_gamma", lg.str()},
                      {"profile", m.profile}};
  if (m.profile == "exponential") params["exponential_p"] = p.str();
  if (m.profile == "power") params["power_p"] = p.str();
  return params;
}

// The straight colours of the scene's quads (one object id each).
std::vector<glm::vec3> quad_colors(const RawParams& scene_params) {
  RandomQuadsParams q;
  q.count = std::stoi(scene_params.at("count"));
  q.size = std::stof(scene_params.at("size"));
  q.seed = uint32_t(std::stoul(scene_params.at("seed")));
  q.alpha = kAlpha;
  const Scene scene = make_random_quads(q);
  std::vector<glm::vec3> colors(size_t(q.count));
  for (const Vertex& v : scene.vertices) colors[v.object_id] = glm::vec3(v.color);
  return colors;
}

// Front to back over black with each layer's opacity, as compose.frag.
glm::vec4 composite(const std::vector<glm::vec3>& colors, const std::vector<float>& opacities) {
  glm::vec3 accumulated(0.0f);
  float transmittance = 1.0f;
  for (size_t i = 0; i < colors.size(); ++i) {
    accumulated += transmittance * opacities[i] * colors[i];
    transmittance *= 1.0f - opacities[i];
  }
  return glm::vec4(accumulated, 1.0f - transmittance);
}

// Each pixel's quads, nearest first, read off the plain reference image:
// the ordered subset of the two quads whose composite matches the pixel
// (each pixel must match one clearly).
std::vector<std::vector<int>> read_layers(const Image& reference, const std::vector<glm::vec3>& colors) {
  const std::vector<std::vector<int>> subsets = {{}, {0}, {1}, {0, 1}, {1, 0}};
  std::vector<std::vector<int>> layers(size_t(reference.width * reference.height));
  for (int y = 0; y < reference.height; ++y)
    for (int x = 0; x < reference.width; ++x) {
      std::vector<float> distance;
      for (const auto& subset : subsets) {
        std::vector<glm::vec3> c;
        for (int q : subset) c.push_back(colors[size_t(q)]);
        const glm::vec4 expected = composite(c, std::vector<float>(subset.size(), kAlpha));
        float worst = 0.0f;
        for (int ch = 0; ch < 4; ++ch) worst = std::max(worst, std::abs(expected[ch] - reference.at(x, y, ch)));
        distance.push_back(worst);
      }
      const size_t best = size_t(std::min_element(distance.begin(), distance.end()) - distance.begin());
      EXPECT_LT(distance[best], 1e-5f) << "pixel " << x << ", " << y << " matches no layering";
      layers[size_t(y * reference.width + x)] = subsets[best];
    }
  return layers;
}

constexpr int kNone = -1, kOffImage = -2;

// One fragment of the model: its pixel, quad, layer index (nearest first),
// links left, right, down, up (the same quad's fragment in the adjacent
// pixel, kNone where the quad does not cover it, kOffImage outside the image).
struct Fragment {
  int pixel, quad, layer;
  std::array<int, 4> links;
  float beta = 0.0f, gamma = 0.0f;
  bool fixed_beta = false, fixed_gamma = false;
};

std::vector<Fragment> fragments_of(const std::vector<std::vector<int>>& layers, int w, int h) {
  std::map<std::pair<int, int>, int> index;  // (pixel, quad) -> fragment
  std::vector<Fragment> fragments;
  for (int pixel = 0; pixel < w * h; ++pixel)
    for (size_t l = 0; l < layers[size_t(pixel)].size(); ++l) {
      index[{pixel, layers[size_t(pixel)][l]}] = int(fragments.size());
      fragments.push_back({pixel, layers[size_t(pixel)][l], int(l), {}});
    }
  const int dx[4] = {-1, 1, 0, 0}, dy[4] = {0, 0, -1, 1};
  for (Fragment& f : fragments) {
    const int x = f.pixel % w, y = f.pixel / w;
    for (int d = 0; d < 4; ++d) {
      const int nx = x + dx[d], ny = y + dy[d];
      const auto found = index.find({ny * w + nx, f.quad});
      f.links[size_t(d)] = nx < 0 || ny < 0 || nx >= w || ny >= h ? kOffImage
                           : found == index.end()                  ? kNone
                                                                   : found->second;
    }
  }
  return fragments;
}

// Section 5.3 (stylize_init.comp): fewer than 4 neighbours: beta = 1, fixed;
// deeper than a neighbour: beta = 0, fixed; nearer than one: gamma = 1, fixed.
void set_boundaries(std::vector<Fragment>& fragments) {
  for (Fragment& f : fragments) {
    bool silhouette = false, under = false, over = false;
    for (int link : f.links) {
      silhouette = silhouette || link == kNone;
      if (link < 0) continue;
      under = under || fragments[size_t(link)].layer < f.layer;
      over = over || fragments[size_t(link)].layer > f.layer;
    }
    f.fixed_beta = silhouette || under;
    f.beta = silhouette ? 1.0f : 0.0f;
    f.fixed_gamma = over;
    f.gamma = over ? 1.0f : 0.0f;
  }
}

// One synchronous step of eq. 9 or eq. 8 (normalised Laplacian) on beta and gamma.
void step(std::vector<Fragment>& fragments, const FieldModel& m) {
  const std::vector<Fragment> before = fragments;
  for (Fragment& f : fragments) {
    float most[2] = {0.0f, 0.0f}, difference[2] = {0.0f, 0.0f}, neighbors = 0.0f;
    for (int link : f.links) {
      if (link < 0) continue;
      const Fragment& n = before[size_t(link)];
      most[0] = std::max(most[0], n.beta);
      most[1] = std::max(most[1], n.gamma);
      difference[0] += n.beta - f.beta;  // f is updated after the loop
      difference[1] += n.gamma - f.gamma;
      neighbors += 1.0f;
    }
    if (m.homogeneous) {
      if (neighbors == 0.0f) continue;
      if (!f.fixed_beta) f.beta += m.lambda_beta * (difference[0] / neighbors);
      if (!f.fixed_gamma) f.gamma += m.lambda_gamma * (difference[1] / neighbors);
    } else {
      if (!f.fixed_beta) f.beta = std::max(f.beta, most[0] - m.lambda_beta);
      if (!f.fixed_gamma) f.gamma = std::max(f.gamma, most[1] - m.lambda_gamma);
    }
  }
}

// Eq. 10 / eq. 11 (or none) on a field value clamped to [0, 1].
float profiled(float u, const FieldModel& m) {
  u = std::clamp(u, 0.0f, 1.0f);
  if (m.profile == "exponential") {
    const float floor_value = std::exp(-m.p);
    return (std::exp(-m.p * (1.0f - u) * (1.0f - u)) - floor_value) / (1.0f - floor_value);
  }
  return m.profile == "power" ? std::pow(u, m.p) : u;
}

// The illustration buffer's image of the layering under model `m`: Algorithm
// 3 with alpha_hat = (1 - gamma) (alpha + (1 - alpha) beta), alpha = s (eq. 4;
// one alpha in the scene, so eq. 8 leaves alpha as it is).
Image model_image(const std::vector<std::vector<int>>& layers, const std::vector<glm::vec3>& colors,
                  const FieldModel& m, int w, int h) {
  std::vector<Fragment> fragments = fragments_of(layers, w, h);
  set_boundaries(fragments);
  for (int i = 0; i < m.iterations; ++i) step(fragments, m);
  Image image{w, h, std::vector<float>(size_t(w * h * 4), 0.0f)};
  std::vector<std::vector<glm::vec3>> c(size_t(w * h));
  std::vector<std::vector<float>> opacity(size_t(w * h));
  for (const Fragment& f : fragments) {  // in each pixel nearest first
    c[size_t(f.pixel)].push_back(colors[size_t(f.quad)]);
    const float beta = profiled(f.beta, m), gamma = profiled(f.gamma, m);
    opacity[size_t(f.pixel)].push_back((1.0f - gamma) * (kAlpha + (1.0f - kAlpha) * beta));
  }
  for (int pixel = 0; pixel < w * h; ++pixel) {
    const glm::vec4 v = composite(c[size_t(pixel)], opacity[size_t(pixel)]);
    for (int ch = 0; ch < 4; ++ch) image.rgba[size_t(pixel * 4 + ch)] = v[ch];
  }
  return image;
}

struct TwoQuads {
  std::vector<glm::vec3> colors;
  std::vector<std::vector<int>> layers;
};

const TwoQuads& two_quads() {
  static const TwoQuads quads = [] {
    TwoQuads q;
    q.colors = quad_colors(kTwoQuads);
    const Image& reference = test::harness().reference_image("random_quads", kTwoQuads, kSide, kSide, glm::vec3(0.0f));
    q.layers = read_layers(reference, q.colors);
    return q;
  }();
  return quads;
}

// The largest difference between the technique's image and the model's, for both searches.
void expect_model(const FieldModel& m, const RawParams& extra, double tolerance) {
  const TwoQuads& quads = two_quads();
  const Image expected = model_image(quads.layers, quads.colors, m, kSide, kSide);
  for (const std::string search : {"triangle_index", "heuristic"}) {
    RawParams params = technique_params(m, search);
    params.insert(extra.begin(), extra.end());
    const RunResult r = test::render_once("illustration_buffer", params, "random_quads", kTwoQuads, kSide, kSide);
    const double difference = test::max_abs_difference(r.image, expected);
    std::printf("[ measured ] %s %s n=%d: largest difference to the CPU model %.2g\n", search.c_str(),
                m.homogeneous ? "eq. 8" : "eq. 9", m.iterations, difference);
    EXPECT_LT(difference, tolerance) << search << " " << r.technique_params;
  }
}

TEST(IllustrationBufferFields, TheTwoQuadsHaveSilhouettesHalosAndOverlap) {
  const TwoQuads& quads = two_quads();
  std::vector<Fragment> fragments = fragments_of(quads.layers, kSide, kSide);
  set_boundaries(fragments);
  int silhouettes = 0, halos = 0, under = 0;
  for (const Fragment& f : fragments) {
    silhouettes += f.fixed_beta && f.beta == 1.0f;
    under += f.fixed_beta && f.beta == 0.0f;
    halos += f.fixed_gamma;
  }
  EXPECT_GT(silhouettes, 40);
  EXPECT_GT(halos, 10);
  EXPECT_GT(under, 10);
}

// The comparisons below tell the equations and their lambdas apart: the
// model's images of each differ by far more than the tolerance.
TEST(IllustrationBufferFields, TheModelsImagesDifferBetweenEquationsAndLambdas) {
  const TwoQuads& quads = two_quads();
  const auto image = [&](const FieldModel& m) { return model_image(quads.layers, quads.colors, m, kSide, kSide); };
  FieldModel nine, eight, eight_gamma, eight_long;
  eight.homogeneous = eight_gamma.homogeneous = eight_long.homogeneous = true;
  eight.lambda_beta = eight_gamma.lambda_beta = eight_long.lambda_beta = 1.0f;
  eight_gamma.lambda_gamma = 0.6f;
  eight_long.iterations = 100;
  EXPECT_GT(test::max_abs_difference(image(nine), image(eight)), 0.05);
  EXPECT_GT(test::max_abs_difference(image(eight), image(eight_gamma)), 0.05);
  EXPECT_GT(test::max_abs_difference(image(eight), image(eight_long)), 0.01);
}

// Eq. 8 with the paper's Fig. 9 values (lambda_beta = 1, lambda_gamma = 0.1,
// 20 and 100 steps) and with others, every fragment every step and with
// skip_converged (the same steps over the pixels that can still change).
TEST(IllustrationBufferFields, EquationEightSpreadsBetaAndGammaAsTheCpuModel) {
  FieldModel m;
  m.homogeneous = true;
  m.lambda_beta = 1.0f;
  for (const char* skip : {"false", "true"}) expect_model(m, {{"skip_converged", skip}}, 1e-5);
  m.iterations = 100;
  expect_model(m, {{"skip_converged", "true"}}, 1e-5);
  m.iterations = 7;
  m.lambda_beta = 0.3f;
  m.lambda_gamma = 0.6f;
  expect_model(m, {{"skip_converged", "false"}}, 1e-5);
}

TEST(IllustrationBufferFields, EquationNineSpreadsBetaAndGammaAsTheCpuModel) {
  FieldModel m;
  for (const char* diffusion : {"steps", "auto"}) expect_model(m, {{"diffusion", diffusion}}, 1e-5);
  m.iterations = 4;
  m.lambda_beta = 0.2f;
  m.lambda_gamma = 0.3f;
  expect_model(m, {{"skip_converged", "false"}, {"diffusion", "steps"}}, 1e-5);
}

// Eq. 10 and eq. 11 with Fig. 9's p (3 and 0.3) and others, on either equation's fields.
TEST(IllustrationBufferFields, ProfilesFollowEquationsTenAndElevenAsTheCpuModel) {
  FieldModel m;
  m.profile = "exponential";
  for (float p : {3.0f, 0.5f}) {
    m.p = p;
    expect_model(m, {}, 1e-5);
  }
  m.homogeneous = true;
  m.lambda_beta = 1.0f;
  m.profile = "power";
  for (float p : {0.3f, 2.0f}) {
    m.p = p;
    expect_model(m, {}, 1e-5);
  }
}

// The sweeps reach eq. 9's fixed point: with eq. 8 diffusion=sweep is an
// error naming both parameters, and auto runs the steps.
TEST(IllustrationBufferFields, EquationEightCannotSweepAndAutoSteps) {
  test::gl_context();
  const RawParams sweep = {{"field_diffusion", "homogeneous"}, {"diffusion", "sweep"}};
  const RunSpec spec = test::one_frame("illustration_buffer", sweep, "random_quads", kTwoQuads, kSide);
  const RunResult swept = test::harness().run(spec);
  EXPECT_EQ(swept.status, RunStatus::error);
  EXPECT_NE(swept.message.find("field_diffusion=homogeneous"), std::string::npos) << swept.message;
  EXPECT_NE(swept.message.find("diffusion=steps"), std::string::npos) << swept.message;
  const RunResult automatic = test::render_once("illustration_buffer", {{"field_diffusion", "homogeneous"}},
                                                "random_quads", kTwoQuads, kSide, kSide);
  EXPECT_NE(automatic.technique_params.find("diffusion=steps"), std::string::npos) << automatic.technique_params;
  EXPECT_EQ(test::extra_counter(automatic, "sweep_diffusion"), 0.0);
  // eq. 9 on the same frame: auto sweeps on a software rasterizer.
  const RunResult plain = test::render_once("illustration_buffer", {}, "random_quads", kTwoQuads, kSide, kSide);
  EXPECT_EQ(test::extra_counter(plain, "sweep_diffusion"), test::gl_context().device().software ? 1.0 : 0.0);
}

// field_diffusion's default is eq. 9: giving it changes no image, bit for
// bit, whatever the diffusion path; eq. 8 gives another image.
TEST(IllustrationBufferFields, TheDefaultIsEquationNineBitForBit) {
  for (const RawParams& params : std::vector<RawParams>{{}, {{"preset", "paper"}}, {{"diffusion", "steps"}},
                                                        {{"skip_converged", "false"}, {"diffusion", "steps"}}}) {
    RawParams nine = params;
    nine["field_diffusion"] = "nonphysical";
    const Image a = test::render_once("illustration_buffer", params, "torus", {}, 48, 48).image;
    const Image b = test::render_once("illustration_buffer", nine, "torus", {}, 48, 48).image;
    EXPECT_EQ(test::max_abs_difference(a, b), 0.0);
    RawParams eight = params;
    eight["field_diffusion"] = "homogeneous";
    if (!eight.contains("diffusion")) eight["diffusion"] = "steps";
    EXPECT_GT(test::max_abs_difference(a, test::render_once("illustration_buffer", eight, "torus", {}, 48, 48).image),
              1e-3);
  }
}

}  // namespace
}  // namespace oit
