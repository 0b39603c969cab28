#include "harness/output/csv_file.h"

#include <csv.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace oit {
namespace {

// libcsv callbacks: a field ends, a record ends.
struct Parse {
  std::vector<CsvRecord> records;
  CsvRecord current;
  size_t line = 1;         // of the chunk being fed
  uint64_t chunk_end = 0;  // offset just past it
};
void end_field(void* text, size_t length, void* data) {
  auto* parse = static_cast<Parse*>(data);
  if (parse->current.fields.empty()) parse->current.line = parse->line;
  parse->current.fields.push_back(length ? std::string(static_cast<const char*>(text), length) : std::string());
}
void end_record(int, void* data) {
  auto* parse = static_cast<Parse*>(data);
  parse->current.end = parse->chunk_end;
  parse->records.push_back(std::move(parse->current));
  parse->current = {};
}
// Spaces around an unquoted field are data (libcsv trims them by default).
int no_space(unsigned char) { return 0; }

std::string lines_text(size_t first, size_t last) {
  return first == last ? "line " + std::to_string(first)
                       : "lines " + std::to_string(first) + "-" + std::to_string(last);
}

}  // namespace

CsvContents parse_csv(std::string_view text, const std::string& path) {
  csv_parser parser;
  if (csv_init(&parser, 0) != 0) throw std::runtime_error("cannot read CSV '" + path + "': libcsv init failed");
  csv_set_space_func(&parser, no_space);
  Parse parse;
  bool failed = false;
  // Fed a line at a time, so each record's end offset is its line's end
  // (libcsv ends a record at CR or LF outside quotes; CRLF's LF is skipped).
  for (size_t position = 0; !failed && position < text.size();) {
    const size_t newline = text.find('\n', position);
    const size_t stop = newline == std::string_view::npos ? text.size() : newline + 1;
    parse.chunk_end = stop;
    failed = csv_parse(&parser, text.data() + position, stop - position, end_field, end_record, &parse) !=
             stop - position;
    position = stop;
    parse.line += newline != std::string_view::npos;
  }
  const size_t complete = parse.records.size();
  failed = failed || csv_fini(&parser, end_field, end_record, &parse) != 0;
  const std::string why = failed ? csv_strerror(csv_error(&parser)) : "";
  csv_free(&parser);
  if (failed) throw std::runtime_error("cannot read CSV '" + path + "': " + why);
  CsvContents contents;
  if (parse.records.size() > complete) {
    contents.torn = std::move(parse.records.back());
    parse.records.pop_back();
  }
  contents.records = std::move(parse.records);
  return contents;
}

CsvContents read_csv_file(const std::string& path, const std::string& kind) {
  if (!std::filesystem::exists(path)) return {};
  require_regular_file(path, kind);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + kind + " '" + path + "'");
  std::stringstream text;
  text << in.rdbuf();
  return parse_csv(text.str(), path);
}

std::vector<std::vector<std::string>> read_csv(const std::string& path) {
  CsvContents contents = read_csv_file(path, "CSV");
  std::vector<std::vector<std::string>> records;
  for (auto& record : contents.records) records.push_back(std::move(record.fields));
  if (contents.torn) records.push_back(std::move(contents.torn->fields));
  return records;
}

std::string csv_escape(const std::string& field) {
  if (field.find_first_of(",\"\n\r") == std::string::npos) return field;
  std::string escaped = "\"";
  for (char c : field) escaped += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return escaped + "\"";
}

std::string csv_line(const std::vector<std::string>& fields) {
  std::string line;
  for (size_t i = 0; i < fields.size(); ++i) line += (i ? "," : "") + csv_escape(fields[i]);
  return line + "\n";
}

std::vector<std::string> field_count_problems(const CsvContents& contents) {
  std::vector<std::string> problems;
  if (contents.records.empty()) return problems;
  const size_t expected = contents.records.front().fields.size();
  for (size_t i = 1; i < contents.records.size(); ++i) {
    const CsvRecord& record = contents.records[i];
    if (record.fields.size() != expected)
      problems.push_back("line " + std::to_string(record.line) + ": " + std::to_string(record.fields.size()) +
                         " fields, expected " + std::to_string(expected));
  }
  return problems;
}

CsvAppender::CsvAppender(const std::string& path, std::vector<std::string> columns, std::string kind,
                         std::string unit, CompletePrefix complete_prefix)
    : file_(path), columns_(std::move(columns)), kind_(std::move(kind)) {
  check_header_and_repair(unit, complete_prefix);
}

void CsvAppender::check_header_and_repair(const std::string& unit, const CompletePrefix& complete_prefix) {
  const auto lock = file_.lock_exclusive();
  const std::string header = csv_line(columns_);
  const std::string text = file_.read_all();
  const CsvContents contents = parse_csv(text, path());
  const bool torn_header = contents.records.empty() && contents.torn &&
                           header.compare(0, text.size(), text) == 0;  // a header cut short
  if (text.find_first_not_of("\r\n") == std::string::npos || torn_header) {
    if (!text.empty()) file_.truncate(0);
    file_.append(header);  // once, under the lock: other writers see it or an empty file
    return;
  }
  if (contents.records.empty() || contents.records.front().fields != columns_)
    throw std::runtime_error(kind_ + " '" + path() + "' exists with different columns; choose another file");
  const std::vector<CsvRecord> rows(contents.records.begin() + 1, contents.records.end());
  const size_t keep = complete_prefix ? complete_prefix(rows) : rows.size();
  const uint64_t cut = keep == 0 ? contents.records.front().end : rows[keep - 1].end;
  if (keep == rows.size() && !contents.torn) return;  // at most blank lines after the last record
  const size_t first_line = keep < rows.size() ? rows[keep].line : contents.torn->line;
  const size_t last_line = contents.torn ? contents.torn->line : rows.back().line;
  const std::string torn_path = path() + ".torn";
  {
    SharedAppendFile kept(torn_path);
    const auto kept_lock = kept.lock_exclusive();
    kept.append(text.substr(cut));
  }
  file_.truncate(cut);
  repair_note_ = kind_ + " '" + path() + "' ended in an incomplete " + unit + " (" +
                 lines_text(first_line, last_line) + (contents.torn ? ", the last cut short without a newline" : "") +
                 "): cut back to the last complete " + unit + " (line " +
                 std::to_string(keep == 0 ? contents.records.front().line : rows[keep - 1].line) + "); the " +
                 std::to_string(text.size() - cut) + " bytes cut are kept in '" + torn_path + "'";
  std::fprintf(stderr, "oitbench: %s\n", repair_note_.c_str());
}

void CsvAppender::append(const std::vector<std::vector<std::string>>& records) {
  std::string text;
  for (const auto& record : records) text += csv_line(record);
  const auto lock = file_.lock_exclusive();
  file_.append(text);
}

CsvContents CsvAppender::read() const {
  const auto lock = file_.lock_shared();
  return parse_csv(file_.read_all(), path());
}

}  // namespace oit
