// Deterministic surface texture for the simulated cameras: a colour for each point of a surface
// from its material, its surface id, the world's texture seed and the point's coordinates on
// the surface (metres), so stereo matching has structure, the same surface looks the same from
// every view and every run, and different surfaces look different. Value noise at a few
// scales, plus the pattern of the material (floor and ceiling tiles, wood grain, poster blobs,
// whiteboard strokes).
//
// The noise lattice comes from seeded permutation tables (1024 cells before it repeats: 25 m
// for the finest 2.5 cm grain, far beyond any stereo search range), not from hashing every
// lattice point: the renderer asks for a colour at every pixel of every frame.
#pragma once

#include <opencv2/core.hpp>

#include <array>
#include <cstdint>

#include "sim/render_faces.h"

namespace rgnav::sim {

// What is fixed for one surface: its material, noise keys and colours (worked out once per
// surface and frame, not per pixel).
struct SurfaceLook
{
  Material material = Material::kWall;
  int key_a = 0, key_b = 0;  // lattice offsets for this surface's noise
  std::array<cv::Vec3f, 4> colours{};
};

class SurfaceTexture
{
 public:
  explicit SurfaceTexture(uint64_t seed);
  // `shade` scales the colours (the face's lighting).
  SurfaceLook look(Material m, uint32_t surface, float shade = 1.0f) const;
  // B, G, R of the point (s, t) [m] on the surface.
  cv::Vec3b colour(const SurfaceLook& look, float s, float t) const;
  cv::Vec3b colour(Material m, uint32_t surface, float s, float t) const { return colour(look(m, surface), s, t); }

 private:
  static constexpr int kCells = 1024;
  // Smooth noise in [0, 1] with unit lattice spacing; `octave` picks an independent lattice.
  float noise(float x, float y, const SurfaceLook& look, int octave) const;

  std::array<uint16_t, kCells> perm_{};
  std::array<float, kCells> value_{};
  uint64_t seed_;
};

}  // namespace rgnav::sim
