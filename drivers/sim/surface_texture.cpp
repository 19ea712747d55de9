#include "sim/surface_texture.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "sim/rng.h"

namespace rgnav::sim {

namespace {

uint64_t mix(uint64_t z)
{
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

float unit(uint64_t h) { return static_cast<float>(h >> 40) * (1.0f / 16777216.0f); }

// A variation of a material's colour (B, G, R) for one surface: brightness and a little hue.
cv::Vec3f tint(const cv::Vec3f& base, float brightness, float hue, uint64_t h)
{
  const float k = 1 - brightness + 2 * brightness * unit(mix(h + 1));
  return {base[0] * k * (1 - hue + 2 * hue * unit(mix(h + 2))), base[1] * k * (1 - hue + 2 * hue * unit(mix(h + 3))),
          base[2] * k * (1 - hue + 2 * hue * unit(mix(h + 4)))};
}

cv::Vec3b to_bytes(const cv::Vec3f& c, float k)
{
  return {cv::saturate_cast<uchar>(c[0] * k), cv::saturate_cast<uchar>(c[1] * k), cv::saturate_cast<uchar>(c[2] * k)};
}

int floor_int(float x)
{
  const int i = static_cast<int>(x);
  return x < static_cast<float>(i) ? i - 1 : i;
}

}  // namespace

SurfaceTexture::SurfaceTexture(uint64_t seed) : seed_(seed)
{
  Rng rng = Rng::derive(seed, 0x7E87u);
  std::iota(perm_.begin(), perm_.end(), uint16_t{0});
  for (int i = kCells - 1; i > 0; --i)
    std::swap(perm_[static_cast<size_t>(i)], perm_[static_cast<size_t>(rng.next_u64() % static_cast<uint64_t>(i + 1))]);
  for (auto& v : value_) v = static_cast<float>(rng.uniform());
}

float SurfaceTexture::noise(float x, float y, const SurfaceLook& look, int octave) const
{
  const int ix = floor_int(x), iy = floor_int(y);
  float tx = x - static_cast<float>(ix), ty = y - static_cast<float>(iy);
  tx = tx * tx * (3 - 2 * tx);
  ty = ty * ty * (3 - 2 * ty);
  constexpr int m = kCells - 1;
  const int ax = (ix + look.key_a + 331 * octave) & m, bx = (ax + 1) & m;
  const int oy = iy + look.key_b + 577 * octave;
  const int pa = perm_[static_cast<size_t>(ax)], pb = perm_[static_cast<size_t>(bx)];
  const float a = value_[perm_[static_cast<size_t>((pa + oy) & m)]], b = value_[perm_[static_cast<size_t>((pb + oy) & m)]];
  const float c = value_[perm_[static_cast<size_t>((pa + oy + 1) & m)]], d = value_[perm_[static_cast<size_t>((pb + oy + 1) & m)]];
  return (a + (b - a) * tx) * (1 - ty) + (c + (d - c) * tx) * ty;
}

SurfaceLook SurfaceTexture::look(Material m, uint32_t surface, float shade) const
{
  SurfaceLook l;
  l.material = m;
  const uint64_t id = mix(seed_ * 0x9E3779B97F4A7C15ull ^ (static_cast<uint64_t>(surface) << 8));
  l.key_a = static_cast<int>(id % kCells);
  l.key_b = static_cast<int>((id >> 20) % kCells);
  auto& c = l.colours;
  switch (m) {
    case Material::kWall: c[0] = tint({175, 190, 200}, 0.12f, 0.06f, id); break;
    case Material::kFloor: c[0] = tint({95, 95, 100}, 0.1f, 0.05f, id); break;
    case Material::kCeiling: c[0] = {225, 228, 230}; c[1] = {110, 110, 110}; break;
    case Material::kDoorLeaf: c[0] = tint({50, 95, 150}, 0.15f, 0.05f, id); break;
    case Material::kDoorFrame: c[0] = {70, 70, 75}; break;
    case Material::kBox: c[0] = tint({120, 140, 160}, 0.3f, 0.3f, id); break;
    case Material::kTableTop: c[0] = tint({60, 110, 165}, 0.12f, 0.05f, id); break;
    case Material::kTableLeg: c[0] = {55, 55, 60}; break;
    case Material::kPerson:
      c[0] = tint({90, 60, 50}, 0.4f, 0.3f, id);        // trousers
      c[1] = tint({120, 120, 150}, 0.4f, 0.5f, id + 7);  // shirt
      c[2] = {120, 150, 190};                            // head
      break;
    case Material::kPoster:
      c[0] = tint({40, 40, 40}, 0.3f, 0.2f, id);
      c[1] = tint({30, 60, 200}, 0.3f, 0.4f, id + 1);
      c[2] = tint({190, 120, 40}, 0.3f, 0.4f, id + 2);
      c[3] = tint({60, 200, 220}, 0.3f, 0.3f, id + 3);
      break;
    case Material::kWhiteboard: c[0] = {235, 238, 240}; c[1] = tint({150, 60, 30}, 0.3f, 0.3f, id); break;
  }
  for (auto& x : c) x *= shade;
  return l;
}

cv::Vec3b SurfaceTexture::colour(const SurfaceLook& l, float s, float t) const
{
  // Fine grain (2-3 cm) and blotches (15-25 cm): texture for the matcher at any distance.
  auto grain = [&](float cell) { return noise(s / cell, t / cell, l, 0); };
  auto blotch = [&](float cell) { return noise(s / cell, t / cell, l, 1); };
  const auto& c = l.colours;
  switch (l.material) {
    case Material::kWall: return to_bytes(c[0], 0.62f + 0.22f * grain(0.025f) + 0.28f * blotch(0.2f));
    case Material::kFloor: {
      // 0.5 m carpet tiles, each a little different, with a fine weave.
      const float tile = noise(static_cast<float>(floor_int(s * 2.0f)), static_cast<float>(floor_int(t * 2.0f)), l, 2);
      return to_bytes(c[0], 0.6f + 0.25f * tile + 0.35f * grain(0.02f));
    }
    case Material::kCeiling: {
      // 0.6 m tiles with dark seams.
      const float ms = std::fabs(std::fmod(s, 0.6f)), mt = std::fabs(std::fmod(t, 0.6f));
      if (ms < 0.02f || mt < 0.02f) return to_bytes(c[1], 1.0f);
      return to_bytes(c[0], 0.75f + 0.2f * grain(0.03f) + 0.05f * blotch(0.3f));
    }
    case Material::kDoorLeaf: {
      // Wood: grain stretched along the leaf's height.
      const float g = noise(s / 0.015f, t / 0.4f, l, 0) * 0.6f + noise(s / 0.06f, t / 1.2f, l, 1) * 0.4f;
      return to_bytes(c[0], 0.6f + 0.55f * g);
    }
    case Material::kDoorFrame: return to_bytes(c[0], 0.7f + 0.4f * grain(0.03f));
    case Material::kBox: return to_bytes(c[0], 0.55f + 0.3f * grain(0.03f) + 0.3f * blotch(0.15f));
    case Material::kTableTop: {
      const float g = noise(s / 0.3f, t / 0.012f, l, 0) * 0.6f + noise(s / 0.8f, t / 0.05f, l, 1) * 0.4f;
      return to_bytes(c[0], 0.55f + 0.6f * g);
    }
    case Material::kTableLeg: return to_bytes(c[0], 0.7f + 0.5f * grain(0.02f));
    case Material::kPerson: return to_bytes(c[t < 0.85f ? 0 : (t < 1.45f ? 1 : 2)], 0.6f + 0.5f * grain(0.02f));
    case Material::kPoster: {
      // Bold blobs in a few colours.
      const float b = blotch(0.12f) * 0.7f + grain(0.04f) * 0.3f;
      return to_bytes(c[static_cast<size_t>(std::clamp(static_cast<int>(b * 4.0f), 0, 3))], 0.9f + 0.15f * grain(0.01f));
    }
    case Material::kWhiteboard: {
      // White, with marker strokes in patches of writing.
      const bool stroke = noise(s / 0.05f, t / 0.015f, l, 2) > 0.78f && blotch(0.25f) > 0.45f;
      if (stroke) return to_bytes(c[1], 0.8f);
      return to_bytes(c[0], 0.9f + 0.1f * grain(0.05f));
    }
  }
  return {128, 128, 128};
}

}  // namespace rgnav::sim
