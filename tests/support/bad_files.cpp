#include "bad_files.h"

#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>

namespace rgnav::testing {

namespace fs = std::filesystem;

std::string random_bytes(size_t n, uint32_t seed)
{
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  std::string s(n, '\0');
  for (auto& c : s) c = static_cast<char>(byte(rng));
  return s;
}

void write_bytes(const std::string& path, const std::string& bytes)
{
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!f) throw std::runtime_error("cannot write " + path);
}

std::vector<BadFile> write_bad_files(const std::string& dir, const std::string& name, const std::string& valid,
                                     size_t keep)
{
  if (keep == std::string::npos) keep = valid.size() / 2;
  if (keep == 0 || keep >= valid.size()) throw std::invalid_argument("a truncated file keeps part of the content");
  std::vector<BadFile> files{{"random", dir + "/random_" + name}, {"empty", dir + "/empty_" + name},
                             {"truncated", dir + "/truncated_" + name}};
  write_bytes(files[0].path, random_bytes(4096));
  write_bytes(files[1].path, "");
  write_bytes(files[2].path, valid.substr(0, keep));
  return files;
}

ToolRun run_tool(std::vector<std::string> argv, const std::string& capture_dir, std::chrono::milliseconds timeout)
{
  static int runs = 0;
  ChildOptions o;
  const std::string stem = capture_dir + "/run" + std::to_string(++runs);
  o.stdout_path = stem + ".stdout";
  o.stderr_path = stem + ".stderr";
  ToolRun r;
  r.status = run_to_completion(std::move(argv), timeout, o);
  r.out = read_file(o.stdout_path);
  r.err = read_file(o.stderr_path);
  return r;
}

bool nothing_written(const std::string& path)
{
  std::error_code ec;
  if (!fs::exists(path, ec)) return true;
  if (!fs::is_directory(path, ec)) return false;
  for (const auto& e : fs::recursive_directory_iterator(path, ec))
    if (!e.is_directory()) return false;
  return true;
}

}  // namespace rgnav::testing
