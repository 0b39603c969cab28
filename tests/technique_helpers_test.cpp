// The helpers harness/toolkit gives every technique, checked on their own:
// Frame::near_far for both kinds of projection, make_technique for
// constructors with and without parameters, and SlotsPerPixel's k (fixed,
// or counted and capped with k=auto) with the figures it reports, and
// SlotCursors' check of a linearized fill's ranges on the host.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "harness/toolkit/list_length_pass.h"
#include "harness/toolkit/technique.h"
#include "scenes/scene_library.h"
#include "tests/gl_fixture.h"

namespace oit {
namespace {

// The schema of the two k-buffer parameters SlotsPerPixel reads.
const ParamSchema kSlotSchema{ParamSpec::integer_or_auto("k", "16", 1, 64, "slots"),
                              ParamSpec::integer("auto_k_memory_mb", 1024, 1, 1 << 20, "cap")};

double figure(const std::vector<Figure>& figures, const std::string& name) {
  const std::optional<double> value = find_figure(figures, name);
  EXPECT_TRUE(value.has_value()) << "no figure " << name;
  return value.value_or(-1.0);
}

TEST(TechniqueHelpers, NearFarOfPerspectiveAndOrthographicProjections) {
  test::gl_context();
  const Scene quads = load_scene("quads", {{"layers", "2"}});
  const SceneGpu gpu(quads);
  StageClock clock(ClockKind::wall);
  Frame frame{gpu, glm::mat4(1.0f), glm::perspective(glm::radians(45.0f), 1.5f, 0.25f, 40.0f), 8, 8,
              glm::vec3(0.0f), 0, clock};
  EXPECT_NEAR(frame.near_far().x, 0.25f, 1e-6f);
  EXPECT_NEAR(frame.near_far().y, 40.0f, 1e-3f);
  // An orthographic near plane may lie behind the eye.
  frame.projection = glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, -2.0f, 5.0f);
  EXPECT_NEAR(frame.near_far().x, -2.0f, 1e-6f);
  EXPECT_NEAR(frame.near_far().y, 5.0f, 1e-6f);
}

struct WithParameters final : Technique {
  explicit WithParameters(const ParamSet& params) : k(int(params.integer("k"))) {}
  void resize(int, int) override {}
  void render(const Frame&) override {}
  TechniqueCounters counters() const override { return {}; }
  int k;
};
struct WithoutParameters final : Technique {
  void resize(int, int) override {}
  void render(const Frame&) override {}
  TechniqueCounters counters() const override { return {}; }
};

TEST(TechniqueHelpers, MakeTechniquePassesTheParametersWhereTheConstructorTakesThem) {
  const ParamSet params(kSlotSchema, {{"k", "7"}}, "test");
  const std::unique_ptr<Technique> with = make_technique<WithParameters>(params);
  EXPECT_EQ(dynamic_cast<const WithParameters&>(*with).k, 7);
  const std::unique_ptr<Technique> without = make_technique<WithoutParameters>(params);
  EXPECT_NE(dynamic_cast<const WithoutParameters*>(without.get()), nullptr);
}

// 3 quads over the whole view: every pixel's list holds 3 fragments.
class SlotsPerPixelTest : public ::testing::Test {
 protected:
  SlotsPerPixelTest() : quads_(load_scene("quads", {{"layers", "3"}})) {
    test::gl_context();
    gpu_ = std::make_unique<SceneGpu>(quads_);
  }
  // k for one frame of the quads at size x size, with `bytes_per_slot`.
  int k_of(SlotsPerPixel& slots, int size, uint64_t bytes_per_slot) {
    slots.resize(size, size, bytes_per_slot, bytes_per_slot);
    const Frame frame{*gpu_, quads_.camera.view, quads_.camera.projection(1.0f), size, size, glm::vec3(0.0f), 0,
                      clock_};
    return slots.for_frame(frame);
  }
  Scene quads_;
  std::unique_ptr<SceneGpu> gpu_;
  StageClock clock_{ClockKind::wall};
};

TEST_F(SlotsPerPixelTest, AFixedKIsTheParameterAndCountsNothing) {
  SlotsPerPixel slots(ParamSet(kSlotSchema, {{"k", "5"}}, "test"), 64);
  EXPECT_FALSE(slots.automatic());
  EXPECT_EQ(k_of(slots, 16, 24), 5);
  EXPECT_EQ(slots.passes(), 0u);
  EXPECT_EQ(slots.bytes_allocated(), 0u);
  std::vector<Figure> figures;
  slots.add_figures(figures, 5);
  ASSERT_EQ(figures.size(), 1u);
  EXPECT_EQ(figure(figures, "k_used"), 5.0);
}

TEST_F(SlotsPerPixelTest, AutoIsTheViewsLongestList) {
  SlotsPerPixel slots(ParamSet(kSlotSchema, {{"k", "auto"}}, "test"), 64);
  EXPECT_TRUE(slots.automatic());
  EXPECT_EQ(k_of(slots, 16, 24), 3);
  EXPECT_EQ(slots.passes(), 1u);
  EXPECT_EQ(slots.bytes_allocated(), 16u * 16u * 4u);  // the R32F count target
  std::vector<Figure> figures;
  slots.add_figures(figures, 3);
  EXPECT_EQ(figure(figures, "k_used"), 3.0);
  EXPECT_EQ(figure(figures, "longest_list"), 3.0);
  EXPECT_EQ(figure(figures, "k_cap"), 64.0);
  EXPECT_EQ(figure(figures, "k_capped"), 0.0);
}

TEST_F(SlotsPerPixelTest, AutoIsCappedByTheMemoryCap) {
  // 1 MiB of 4096-byte slots over 16 x 16 pixels: 1 slot per pixel.
  SlotsPerPixel slots(ParamSet(kSlotSchema, {{"k", "auto"}, {"auto_k_memory_mb", "1"}}, "test"), 64);
  EXPECT_EQ(k_of(slots, 16, 4096), 1);
  std::vector<Figure> figures;
  slots.add_figures(figures, 1);
  EXPECT_EQ(figure(figures, "longest_list"), 3.0);
  EXPECT_EQ(figure(figures, "k_cap"), 1.0);
  EXPECT_EQ(figure(figures, "k_capped"), 1.0);
}

// A pixel whose cursor did not end at the end of its range is counted, with
// either way of taking slots (both exist on llvmpipe). The cursors start at
// the values they are given: the offsets (as before a fill), then each
// pixel's end (as after a fill that matched the counts), then the ends with
// one empty pixel given a fragment the counting missed.
TEST(TechniqueHelpers, SlotCursorsCountThePixelsWhoseFillEndedElsewhere) {
  test::gl_context();
  const std::vector<float> counts = {0, 2, 1, 0, 3, 0, 0, 1};  // 4 x 2 pixels
  std::vector<uint32_t> offsets;
  offsets_from_counts(counts, offsets);
  std::vector<uint32_t> ends(offsets.begin() + 1, offsets.end());
  std::vector<uint32_t> one_more = ends;
  one_more[3] += 1;
  const Buffer starts_buffer = make_buffer(GLsizeiptr(offsets.size() * 4), offsets.data(), 0);
  const Buffer ends_buffer = make_buffer(GLsizeiptr(ends.size() * 4), ends.data(), 0);
  const Buffer one_more_buffer = make_buffer(GLsizeiptr(one_more.size() * 4), one_more.data(), 0);
  for (const SlotFill fill : {SlotFill::atomic, SlotFill::framebuffer_fetch}) {
    ASSERT_EQ(missing_slot_fill_feature(fill, test::gl_context().device()), "");
    SlotCursors cursors(fill);
    cursors.resize(4, 2, "test");
    cursors.start(starts_buffer);
    EXPECT_EQ(cursors.count_mismatched(offsets), 4u) << "the four pixels with fragments, before any fill";
    cursors.start(ends_buffer);
    EXPECT_EQ(cursors.count_mismatched(offsets), 0u);
    cursors.start(one_more_buffer);
    EXPECT_EQ(cursors.count_mismatched(offsets), 1u);
    EXPECT_THROW(cursors.count_mismatched(std::vector<uint32_t>(3, 0u)), std::logic_error);
  }
}

}  // namespace
}  // namespace oit
