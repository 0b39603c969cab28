#pragma once
// Dear ImGui widgets generated from a parameter schema (base/params.h):
// integer and real parameters get sliders over their range (integers that
// accept "auto" also an "auto" checkbox beside it), booleans a checkbox,
// choices a combo box, paths a text field applied on Enter. Nothing here
// knows any technique or scene.
#include <string>

#include "base/params.h"

namespace oit {

// Edits `values` (the text the user would pass as --set key=value); a
// parameter absent from `values` shows its default, and a value set back
// to its default is removed so command lines stay short. Returns true when
// something changed. Ctrl+click on a slider types a value, which may lie
// outside the range: validation (ParamSet) is the caller's, so the
// schema's own message can be shown.
bool edit_params(const std::string& scope, const ParamSchema& schema, RawParams& values);

// A real parameter's value as text that reads back to the same double.
std::string real_text(double value);

}  // namespace oit
