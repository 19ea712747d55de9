#include "importers/line_reader.h"

#include <stdexcept>

#include "importers/log_records.h"

namespace rgnav::importers {

LineReader::LineReader(const std::string& path)
{
  file_ = gzopen(path.c_str(), "rb");
  if (!file_) throw std::runtime_error("cannot open " + path);
  gzbuffer(file_, 1 << 17);
}

LineReader::~LineReader()
{
  if (file_) gzclose(file_);
}

bool LineReader::next(std::string* line)
{
  line->clear();
  if (!error_.empty()) return false;
  char buf[8192];
  bool got_any = false;
  for (;;) {
    if (!gzgets(file_, buf, sizeof buf)) break;
    got_any = true;
    line->append(buf);
    if (!line->empty() && line->back() == '\n') break;
  }
  const bool complete = got_any && !line->empty() && line->back() == '\n';
  if (!complete) {
    // End of data or damage. zlib keeps handing out what it decompressed before a truncated
    // stream (Z_BUF_ERROR), so complete lines are never lost; only a partial last line is.
    int errnum = Z_OK;
    const char* msg = gzerror(file_, &errnum);
    if (errnum != Z_OK && errnum != Z_STREAM_END) {
      error_ = errnum == Z_BUF_ERROR ? "unexpected end of compressed data (truncated file)"
                                     : std::string("read error: ") + (msg ? msg : "?");
      return false;
    }
    if (!got_any) return false;
  }
  while (!line->empty() && (line->back() == '\n' || line->back() == '\r')) line->pop_back();
  ++line_number_;
  return true;
}

void record_end_of_input(const LineReader& reader, ImportedLog* log)
{
  log->lines = reader.line_number();
  if (!reader.error().empty()) {
    log->truncated = true;
    log->issues.push_back({reader.line_number() + 1, reader.error()});
  }
}

}  // namespace rgnav::importers
