#include "scan_mapper/mapper_state_io.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <type_traits>

namespace rgnav::scan_mapper {
namespace {

constexpr char kMagic[8] = {'R', 'G', 'N', 'S', 'M', 'A', 'P', '1'};
constexpr uint32_t kVersion = 1;

uint64_t fnv1a(const std::string& data)
{
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : data) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

class Out
{
 public:
  template <class T>
  void put(const T& v)
  {
    static_assert(std::is_trivially_copyable_v<T>);
    buf.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void pose(const Pose2& p) { put(p.x), put(p.y), put(p.theta); }
  void mat(const Eigen::Matrix3d& m)
  {
    for (int i = 0; i < 9; ++i) put(m(i / 3, i % 3));
  }
  std::string buf;
};

class In
{
 public:
  explicit In(const std::string& b) : buf(b) {}
  template <class T>
  T get()
  {
    T v;
    if (pos + sizeof v > buf.size()) throw std::runtime_error("state file truncated");
    std::memcpy(&v, buf.data() + pos, sizeof v);
    pos += sizeof v;
    return v;
  }
  Pose2 pose()
  {
    Pose2 p;
    p.x = get<double>();
    p.y = get<double>();
    p.theta = get<double>();
    return p;
  }
  Eigen::Matrix3d mat()
  {
    Eigen::Matrix3d m;
    for (int i = 0; i < 9; ++i) m(i / 3, i % 3) = get<double>();
    return m;
  }
  uint64_t count(uint64_t max)
  {
    const auto n = get<uint64_t>();
    if (n > max) throw std::runtime_error("state file corrupt (implausible count)");
    return n;
  }
  const std::string& buf;
  size_t pos = 0;
};

void write_fully(int fd, const std::string& data, const std::string& path)
{
  size_t off = 0;
  while (off < data.size()) {
    const ssize_t n = ::write(fd, data.data() + off, data.size() - off);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw std::runtime_error("writing " + path + ": " + std::strerror(errno));
    off += static_cast<size_t>(n);
  }
}

}  // namespace

void save_state(const MapperState& state, const std::string& path)
{
  Out o;
  o.put(static_cast<uint64_t>(state.nodes.size()));
  for (const auto& n : state.nodes) {
    o.put(n.scan.utime), o.put(n.scan.scan_id), o.put(n.scan.angle_min), o.put(n.scan.angle_increment);
    o.put(n.scan.range_min), o.put(n.scan.range_max);
    o.put(static_cast<uint64_t>(n.scan.ranges.size()));
    for (float r : n.scan.ranges) o.put(r);
    o.pose(n.odom_from_base), o.pose(n.map_from_base), o.pose(n.published);
    o.mat(n.covariance);
    o.put(static_cast<int32_t>(n.revision)), o.put(n.path_m);
    o.put(static_cast<uint64_t>(n.points.size()));
    for (const auto& p : n.points) o.put(p.x()), o.put(p.y());
  }
  o.put(static_cast<uint64_t>(state.edges.size()));
  for (const auto& e : state.edges) {
    o.put(static_cast<int32_t>(e.from)), o.put(static_cast<int32_t>(e.to)), o.pose(e.from_from_to);
    o.mat(e.information);
    o.put(static_cast<uint8_t>(e.robust));
  }
  std::string file(kMagic, sizeof kMagic);
  file.append(reinterpret_cast<const char*>(&kVersion), sizeof kVersion);
  const uint64_t sum = fnv1a(o.buf);
  const uint64_t len = o.buf.size();
  file.append(reinterpret_cast<const char*>(&len), sizeof len);
  file.append(reinterpret_cast<const char*>(&sum), sizeof sum);
  file += o.buf;

  const std::filesystem::path target(path);
  if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path());
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error("cannot create " + tmp + ": " + std::strerror(errno));
  try {
    write_fully(fd, file, tmp);
    if (::fsync(fd) != 0) throw std::runtime_error("fsync " + tmp + ": " + std::strerror(errno));
  } catch (...) {
    ::close(fd);
    ::unlink(tmp.c_str());
    throw;
  }
  ::close(fd);
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    throw std::runtime_error("rename " + tmp + " -> " + path + ": " + std::strerror(errno));
  const std::string dir = target.has_parent_path() ? target.parent_path().string() : ".";
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

std::optional<MapperState> load_state(const std::string& path)
{
  if (!std::filesystem::exists(path)) return std::nullopt;
  std::ifstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error("cannot read " + path);
  const std::string file((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const size_t header = sizeof kMagic + sizeof kVersion + 2 * sizeof(uint64_t);
  if (file.size() < header || std::memcmp(file.data(), kMagic, sizeof kMagic) != 0)
    throw std::runtime_error(path + " is not a scan mapper state file");
  uint32_t version;
  uint64_t len, sum;
  std::memcpy(&version, file.data() + sizeof kMagic, sizeof version);
  std::memcpy(&len, file.data() + sizeof kMagic + sizeof version, sizeof len);
  std::memcpy(&sum, file.data() + sizeof kMagic + sizeof version + sizeof len, sizeof sum);
  if (version != kVersion) throw std::runtime_error(path + ": unsupported state version " + std::to_string(version));
  if (file.size() - header != len) throw std::runtime_error(path + ": state file truncated");
  const std::string body = file.substr(header);
  if (fnv1a(body) != sum) throw std::runtime_error(path + ": state file checksum mismatch");
  In in(body);
  MapperState st;
  const uint64_t nn = in.count(10'000'000);
  st.nodes.resize(nn);
  for (auto& n : st.nodes) {
    n.scan.utime = in.get<int64_t>();
    n.scan.scan_id = in.get<int64_t>();
    n.scan.angle_min = in.get<float>();
    n.scan.angle_increment = in.get<float>();
    n.scan.range_min = in.get<float>();
    n.scan.range_max = in.get<float>();
    n.scan.ranges.resize(in.count(100000));
    for (auto& r : n.scan.ranges) r = in.get<float>();
    n.odom_from_base = in.pose();
    n.map_from_base = in.pose();
    n.published = in.pose();
    n.covariance = in.mat();
    n.revision = in.get<int32_t>();
    n.path_m = in.get<double>();
    n.points.resize(in.count(100000));
    for (auto& p : n.points) {
      const double x = in.get<double>();
      p = Eigen::Vector2d(x, in.get<double>());
    }
  }
  const uint64_t ne = in.count(100'000'000);
  st.edges.resize(ne);
  for (auto& e : st.edges) {
    e.from = in.get<int32_t>();
    e.to = in.get<int32_t>();
    e.from_from_to = in.pose();
    e.information = in.mat();
    e.robust = in.get<uint8_t>() != 0;
    if (e.from < 0 || e.to < 0 || static_cast<uint64_t>(e.from) >= nn || static_cast<uint64_t>(e.to) >= nn)
      throw std::runtime_error(path + ": state file corrupt (edge to a missing node)");
  }
  if (in.pos != body.size()) throw std::runtime_error(path + ": state file has trailing data");
  return st;
}

}  // namespace rgnav::scan_mapper
