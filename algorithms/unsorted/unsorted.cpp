// unsorted: alpha blending in submission order, no sorting at all. The speed
// floor and the error ceiling of every comparison.
#include "harness/toolkit/technique.h"
#include "harness/gl/shader_program.h"

namespace oit {
namespace {

class Unsorted final : public Technique {
 public:
  Unsorted() : program_(build_geometry_program("algorithms/unsorted/unsorted.frag")) {}

  void resize(int, int) override {}

  void render(const Frame& frame) override {
    auto fill = frame.clock.stage("fill");
    frame.bind_target();
    glEnable(GL_BLEND);
    // rgb: src over dst; alpha accumulates coverage 1 - prod(1 - a).
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(program_.id());
    frame.set_shared_uniforms(program_.id());
    frame.scene.draw();
    glDisable(GL_BLEND);
  }

  TechniqueCounters counters() const override {
    TechniqueCounters c;
    c.passes = 1;
    return c;
  }

 private:
  Program program_;
};

}  // namespace

void register_technique_unsorted(TechniqueRegistry& registry) {
  registry.add({
      .id = "unsorted",
      .display_name = "Unsorted alpha blending",
      .paper = "(baseline)",
      .stages = {"fill"},
      .create = make_technique<Unsorted>,
  });
}

}  // namespace oit
