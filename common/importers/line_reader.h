// Reads a text file line by line, gzip-compressed or plain (zlib reads both transparently),
// and tells a clean end from a truncated or corrupt compressed stream.
#pragma once

#include <zlib.h>

#include <string>

namespace rgnav::importers {

class LineReader
{
 public:
  // Throws std::runtime_error if the file cannot be opened.
  explicit LineReader(const std::string& path);
  ~LineReader();
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  // Next line without its newline; false at the end or on a read error (see error()).
  bool next(std::string* line);
  int64_t line_number() const { return line_number_; }
  // Non-empty when reading stopped because the stream is damaged (e.g. truncated gzip).
  const std::string& error() const { return error_; }

 private:
  gzFile file_ = nullptr;
  int64_t line_number_ = 0;
  std::string error_;
};

struct ImportedLog;

// Records how reading a text log ended: the number of lines read and, when the stream was
// damaged, the log is marked truncated with an issue on the line after the last good one.
void record_end_of_input(const LineReader& reader, ImportedLog* log);

}  // namespace rgnav::importers
