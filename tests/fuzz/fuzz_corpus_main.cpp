// Writes the seed corpus for decode_fuzzer: for every type (in RGNAV_FOR_EACH_TYPE order, the
// fuzzer's first byte) a few valid sample encodings, so libFuzzer mutates from real messages.
// Usage: rgnav_fuzz_corpus DIR
#include <fstream>
#include <iostream>

#include "bus/typed.h"
#include "sample_messages.h"

namespace {

int index_ = 0;
std::string dir_;

template <class T>
void write_seeds(const char* name)
{
  for (uint32_t v = 0; v < 3; ++v) {
    std::vector<uint8_t> buf;
    std::string why;
    if (!rgnav::bus::encode(rgnav::testing::sample<T>(v), &buf, &why)) {
      std::cerr << name << ": " << why << "\n";
      std::exit(1);
    }
    std::ofstream out(dir_ + "/" + name + "_" + std::to_string(v), std::ios::binary);
    const auto type_byte = static_cast<char>(index_);
    out.write(&type_byte, 1);
    out.write(reinterpret_cast<const char*>(buf.data()), static_cast<std::streamsize>(buf.size()));
  }
  ++index_;
}

}  // namespace

int main(int argc, char** argv)
{
  if (argc != 2) {
    std::cerr << "usage: rgnav_fuzz_corpus DIR\n";
    return 2;
  }
  dir_ = argv[1];
#define RGNAV_SEEDS(T) write_seeds<rgnav::T>(#T);
  RGNAV_FOR_EACH_TYPE(RGNAV_SEEDS)
#undef RGNAV_SEEDS
  std::cout << "wrote seeds for " << index_ << " types to " << dir_ << "\n";
  return 0;
}
