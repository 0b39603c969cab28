#pragma once
// CSV files that several processes append to (bench's results, stress's
// verdicts): read with Debian's libcsv (RFC 4180: quoted fields may hold
// commas, doubled quotes and newlines; no trimming; LF or CRLF line ends),
// appended under an flock one unit at a time through SharedAppendFile, and
// checked on opening: a foreign header is refused, a torn end is cut back.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "harness/output/output_file.h"

namespace oit {

struct CsvRecord {
  std::vector<std::string> fields;
  size_t line = 0;   // where it starts, from 1
  uint64_t end = 0;  // byte offset just past its line end
};

struct CsvContents {
  std::vector<CsvRecord> records;  // the header first; complete records only
  // What follows the last complete record without ending a record (a line
  // cut short by a crash or a full disk, no final newline), as libcsv reads it.
  std::optional<CsvRecord> torn;
};

// Throws naming `path` when libcsv cannot read `text`.
CsvContents parse_csv(std::string_view text, const std::string& path);

// The file at `path` (a `kind` such as "results CSV", named in errors);
// nothing when it is missing. Throws unless it is a readable regular file.
CsvContents read_csv_file(const std::string& path, const std::string& kind);

// Every record of a CSV file, header first, a torn last one included. A
// missing or empty file has none. Throws naming the path.
std::vector<std::vector<std::string>> read_csv(const std::string& path);

std::string csv_escape(const std::string& field);
// Fields escaped, joined by commas, ended by a newline.
std::string csv_line(const std::vector<std::string>& fields);

// "line 7: 85 fields, expected 46" for each record but the header whose
// field count is not the header's.
std::vector<std::string> field_count_problems(const CsvContents& contents);

// Appends records to a CSV with a fixed header. Opening takes the exclusive
// lock and then: writes the header into an empty file; refuses a file whose
// first line is another header (naming the file and `kind`); and cuts a torn
// end back to the last complete unit, keeping the bytes cut in PATH.torn and
// saying so on stderr and in repair_note(). A unit (named `unit` in
// messages) is a record unless `complete_prefix` (given the records after
// the header) says how many of them form complete units.
class CsvAppender {
 public:
  using CompletePrefix = std::function<size_t(const std::vector<CsvRecord>& rows)>;
  CsvAppender(const std::string& path, std::vector<std::string> columns, std::string kind,
              std::string unit = "row", CompletePrefix complete_prefix = {});

  // The records as one unit: one write under the exclusive lock, synced;
  // nothing of them stays when it fails. Throws naming the file.
  void append(const std::vector<std::vector<std::string>>& records);
  // The file as it is now, read under the shared lock.
  CsvContents read() const;
  const std::string& path() const { return file_.path(); }
  const std::string& repair_note() const { return repair_note_; }

 private:
  void check_header_and_repair(const std::string& unit, const CompletePrefix& complete_prefix);

  SharedAppendFile file_;
  std::vector<std::string> columns_;
  std::string kind_;
  std::string repair_note_;
};

}  // namespace oit
