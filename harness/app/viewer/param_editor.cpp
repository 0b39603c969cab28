#include "harness/app/viewer/param_editor.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>

namespace oit {
namespace {

const std::string& current_text(const ParamSpec& spec, const RawParams& values) {
  auto it = values.find(spec.name);
  return it == values.end() ? spec.default_value : it->second;
}

void store(const ParamSpec& spec, const std::string& text, RawParams& values) {
  if (text == spec.default_value) values.erase(spec.name);
  else values[spec.name] = text;
}

// Text that does not parse (only possible for values typed elsewhere)
// shows as the default; validation reports the real problem.
int64_t parse_integer(const std::string& text, const std::string& fallback) {
  char* end = nullptr;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  return end && *end == '\0' && !text.empty() ? v : std::strtoll(fallback.c_str(), nullptr, 10);
}

double parse_real(const std::string& text, const std::string& fallback) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  return end && *end == '\0' && !text.empty() ? v : std::strtod(fallback.c_str(), nullptr);
}

// Logarithmic sliders for wide ranges (k of 1..1024, pool sizes), linear
// for narrow ones where every step matters.
ImGuiSliderFlags slider_flags(const ParamSpec& spec) {
  return spec.min >= 0.0 && spec.max - spec.min > 256.0 ? ImGuiSliderFlags_Logarithmic : ImGuiSliderFlags_None;
}

bool edit_one(const ParamSpec& spec, RawParams& values) {
  const std::string& text = current_text(spec, values);
  switch (spec.type) {
    case ParamType::integer: {
      // A number the slider can show: the default, or the range's low end
      // when the default is "auto".
      const std::string number =
          spec.default_value == "auto" ? std::to_string(int64_t(spec.min)) : spec.default_value;
      bool is_auto = spec.accepts_auto && text == "auto";
      bool changed = false;
      if (spec.accepts_auto) {
        // Checked: the value is "auto" (the slider greys out); unchecked:
        // back to a number.
        if (ImGui::Checkbox(("auto##" + spec.name).c_str(), &is_auto)) {
          store(spec, is_auto ? "auto" : number, values);
          changed = true;
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s = auto: %s", spec.name.c_str(), spec.description.c_str());
        ImGui::SameLine();
      }
      int64_t v = parse_integer(is_auto ? number : text, number);
      const int64_t lo = int64_t(spec.min), hi = int64_t(spec.max);
      ImGui::BeginDisabled(is_auto);
      if (ImGui::SliderScalar(spec.name.c_str(), ImGuiDataType_S64, &v, &lo, &hi, "%lld", slider_flags(spec))) {
        store(spec, std::to_string(v), values);
        changed = true;
      }
      ImGui::EndDisabled();
      return changed;
    }
    case ParamType::real: {
      double v = parse_real(text, spec.default_value);
      if (!ImGui::SliderScalar(spec.name.c_str(), ImGuiDataType_Double, &v, &spec.min, &spec.max, "%.4g",
                               slider_flags(spec)))
        return false;
      store(spec, real_text(v), values);
      return true;
    }
    case ParamType::boolean: {
      bool v = text == "true" || text == "1";
      if (!ImGui::Checkbox(spec.name.c_str(), &v)) return false;
      store(spec, v ? "true" : "false", values);
      return true;
    }
    case ParamType::choice: {
      bool changed = false;
      if (ImGui::BeginCombo(spec.name.c_str(), text.c_str())) {
        for (const auto& choice : spec.choices) {
          if (ImGui::Selectable(choice.c_str(), choice == text)) {
            store(spec, choice, values);
            changed = true;
          }
        }
        ImGui::EndCombo();
      }
      return changed;
    }
    case ParamType::path: {
      // Applied on Enter, not per keystroke: a half-typed path does not
      // exist, and every change rebuilds the technique.
      std::string edited = text;
      if (!ImGui::InputText(spec.name.c_str(), &edited, ImGuiInputTextFlags_EnterReturnsTrue)) return false;
      store(spec, edited, values);
      return true;
    }
  }
  return false;
}

}  // namespace

std::string real_text(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  // Prefer the short form when it reads back the same.
  char shorter[64];
  std::snprintf(shorter, sizeof shorter, "%.6g", value);
  return std::strtod(shorter, nullptr) == value ? shorter : buffer;
}

bool edit_params(const std::string& scope, const ParamSchema& schema, RawParams& values) {
  bool changed = false;
  ImGui::PushID(scope.c_str());
  for (const auto& spec : schema) {
    changed |= edit_one(spec, values);
    if (ImGui::IsItemHovered()) {
      ImGui::SetTooltip("%s\nrange %s, default %s\n%s", spec.description.c_str(), spec.range_text().c_str(),
                        spec.default_value.empty() ? "(none)" : spec.default_value.c_str(),
                        spec.type == ParamType::path ? "press Enter to apply" : "Ctrl+click a slider to type a value");
    }
  }
  ImGui::PopID();
  return changed;
}

}  // namespace oit
