#pragma once
// The sweep options of `oitbench bench` and `pareto` and of oitbench_gbench,
// declared once so the three take the same flags with the same meaning, and
// the scene and technique options the other commands share.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/suggest.h"
#include "harness/app/sweep.h"

namespace oit {

// CLI11's check that a value is one of `values`, saying which it is not and
// the closest one ("'wal' is not one of auto, gl, wall, both; did you mean wall?").
inline CLI::Validator one_of(std::vector<std::string> values) {
  std::string list, braces;
  for (const auto& value : values) {
    list += (list.empty() ? "" : ", ") + value;
    braces += (braces.empty() ? "" : ",") + value;
  }
  return CLI::Validator(
      [values, list](std::string& text) -> std::string {
        for (const auto& value : values)
          if (text == value) return "";
        return "'" + text + "' is not one of " + list + did_you_mean(text, values);
      },
      "{" + braces + "}");
}

// `size_note` follows "repeatable" in --size's help (pareto's says why its
// default is smaller). Defaults come from `sweep` as the caller set it.
inline void add_sweep_cli_options(CLI::App* command, SweepOptions& sweep, const std::string& size_note = "") {
  command->add_option("--technique,-t", sweep.techniques, "technique ids or 'all' (repeatable)");
  command->add_option("--set", sweep.technique_sets,
                      "key=v1,v2 or technique.key=v1,v2: parameter values to sweep (repeatable)");
  command->add_option("--scene,-s", sweep.scenes, "scene ids or files (repeatable)");
  command->add_option("--scene-set", sweep.scene_sets,
                      "key=v1,v2 or scene.key=v1,v2: scene parameter values to sweep (repeatable)");
  command->add_option("--size", sweep.sizes,
                      "WIDTHxHEIGHT or auto: the device's default, 256x256 on software GL, 1920x1080 on a GPU "
                      "(repeatable" + size_note + ")");
  command->add_option("--camera", sweep.cameras,
                      "default, random:N:SEED (one run per view), random:N:SEED@I or max_list[:N:SEED] (repeatable)");
  command->add_option("--frames", sweep.exact_frames,
                      "exactly this many timed frames per run, no precision target (default: precision-driven)")
      ->check(CLI::Range(1, 100000))
      ->default_str("");
  command->add_option("--precision", sweep.repetition.precision,
                      "stop a run once the 95% interval of its median total is within +-this fraction of it")
      ->check(CLI::Range(0.001, 1.0));
  command->add_option("--min-frames", sweep.repetition.frames, "timed frames at least, before the precision is judged")
      ->check(CLI::Range(1, 100000));
  command->add_option("--max-frames", sweep.repetition.max_frames, "timed frames at most per run")->check(CLI::Range(1, 1000000));
  command->add_option("--max-seconds", sweep.repetition.max_seconds, "seconds of timed frames at most per run")
      ->check(CLI::Range(0.001, 1e6));
  command->add_option("--warmup", sweep.repetition.warmup, "untimed frames first, at least (shader compilation, caches)")
      ->check(CLI::Range(0, 1000));
  command->add_option("--warmup-ms", sweep.repetition.warmup_ms,
                      "untimed frames for at least this long and until the frame time is stable (default: the "
                      "device's, 500 on a GPU, 0 on software GL; see `list`)")
      ->check(CLI::Range(0.0, 600000.0));
  command->add_option("--clock", sweep.clock, "auto, gl, wall or both")
      ->check(one_of({"auto", "gl", "wall", "both"}));
  command->add_option("--background", sweep.background, "r,g,b (linear)");
  command->add_option("--scene-rect", sweep.scene_rects,
                      "on, off or on,off: confine techniques to the scene's projected rectangle")
      ->delimiter(',')
      ->check(one_of({"on", "off"}));
  command->add_option("--memory-budget", sweep.memory_budget,
                      "storage a technique may use before the frame is rendered in screen tiles, e.g. 512M or 2G "
                      "(default: the device's, see `list`)");
}

// --scene and --scene-set of the commands that take one scene (render,
// check-order, stats, view).
inline void add_scene_cli_options(CLI::App* command, std::string& scene, std::vector<std::string>& scene_sets) {
  command->add_option("--scene,-s", scene, "scene id or .gltf/.glb/.obj/.off/.ply/.stl file");
  command->add_option("--scene-set", scene_sets, "scene parameter key=value or scene.key=value (repeatable)");
}

// --technique of the commands that run several techniques in turn
// (adaptive, stress, check-order); `note` follows "repeatable".
inline void add_techniques_cli_option(CLI::App* command, std::vector<std::string>& techniques,
                                      const std::string& note = "") {
  command->add_option("--technique,-t", techniques, "technique ids or 'all' (repeatable" + note + ")");
}

// An option given with an empty value (`--memory-budget ""`) would mean
// its default, silently: throws naming it. Call after parsing.
inline void refuse_empty_value(const CLI::App* command, const std::string& option, const std::string& example) {
  const CLI::Option* given = command->get_option_no_throw(option);
  if (!given) return;
  for (const std::string& value : given->results())
    if (value.empty())
      throw std::invalid_argument(option + " is empty: give a value such as " + example +
                                  ", or leave the option out for its default");
}

// What the command line got wrong, with the closest name, for a CLI11
// parse error whose own message names no fix: a word where a subcommand
// belongs ("benchmark": "did you mean bench?") or an option the (sub)command
// does not have ("--frame": "did you mean --frames?"); "" when every word is
// known. `program` starts the message ("oitbench").
inline std::string parse_error_hint(const CLI::App& app, const std::string& program, int argc,
                                    const char* const* argv) {
  auto option_names = [](const CLI::App& command, std::vector<std::string>& names) {
    for (const CLI::Option* option : command.get_options()) {
      for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
      for (const std::string& name : option->get_snames()) names.push_back("-" + name);
    }
  };
  auto is_number = [](const std::string& word) {
    return word.size() > 1 && (std::isdigit(static_cast<unsigned char>(word[1])) || word[1] == '.');
  };
  const std::vector<const CLI::App*> commands = app.get_subcommands([](const CLI::App*) { return true; });
  std::vector<std::string> subcommands;
  for (const CLI::App* command : commands) subcommands.push_back(command->get_name());
  const CLI::App* command = nullptr;
  bool value_follows = false;
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (value_follows || word.empty() || (word[0] == '-' && is_number(word))) {
      value_follows = false;
      continue;
    }
    if (word[0] != '-') {
      if (command || subcommands.empty()) continue;  // a value or a positional argument
      const auto named = std::find(subcommands.begin(), subcommands.end(), word);
      if (named == subcommands.end())
        return program + ": unknown command '" + word + "'" + did_you_mean(word, subcommands);
      command = commands[size_t(named - subcommands.begin())];
      continue;
    }
    const std::string name = word.substr(0, word.find('='));
    const CLI::Option* option = command ? command->get_option_no_throw(name) : nullptr;
    if (!option) option = app.get_option_no_throw(name);
    if (!option) {
      const std::string where = program + (command ? " " + command->get_name() : "");
      if (!command) {
        // `oitbench -t kbuffer bench`: a command's option before the command
        // (the one named later on the line, else the first that has it).
        std::vector<const CLI::App*> owners = commands;
        for (int later = argc - 1; later > i; --later) {
          const auto named = std::find(subcommands.begin(), subcommands.end(), std::string(argv[later]));
          if (named != subcommands.end()) owners.insert(owners.begin(), commands[size_t(named - subcommands.begin())]);
        }
        for (const CLI::App* other : owners)
          if (other->get_option_no_throw(name))
            return where + ": " + name + " is an option of a command: give it after the command (" + program +
                   " " + other->get_name() + " " + name + " ...)";
      }
      // A one-letter option is one edit from every other: only long ones get a suggestion.
      std::vector<std::string> names;
      if (command) option_names(*command, names);
      option_names(app, names);
      const bool long_option = name.rfind("--", 0) == 0;
      return where + ": unknown option '" + name + "'" + (long_option ? did_you_mean(name, names) : "");
    }
    value_follows = word.find('=') == std::string::npos && option->get_type_size_max() > 0;
  }
  return "";
}

// The exit code of a CLI11 parse error: 0 for --help, 1 for a value an
// option refuses (out of its range or set, not convertible), as oitbench's
// own checks of values; 2 for a malformed command line (an unknown
// subcommand or option, a required one missing, an unexpected argument).
inline int parse_error_exit_code(const CLI::ParseError& error) {
  if (error.get_exit_code() == 0) return 0;
  const int code = error.get_exit_code();
  if (code == int(CLI::ExitCodes::ValidationError) || code == int(CLI::ExitCodes::ConversionError)) return 1;
  return 2;
}

// CLI11's message for `error` (help, or the error with the hint from
// parse_error_hint in place of CLI11's words when there is one) and
// parse_error_exit_code.
inline int report_parse_error(const CLI::App& app, const CLI::ParseError& error, const std::string& program, int argc,
                              const char* const* argv) {
  if (error.get_exit_code() == 0) return app.exit(error);
  const std::string hint = parse_error_hint(app, program, argc, argv);
  if (hint.empty()) app.exit(error);
  else std::fprintf(stderr, "%s\nRun with --help for more information.\n", hint.c_str());
  return parse_error_exit_code(error);
}

}  // namespace oit
