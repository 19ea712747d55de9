// Valid sample messages of every rgnav type, for tests. sample<T>(variant) is deterministic in
// `variant`: different variants differ in values, array lengths and enum choices, and every one
// passes bus::encode (wire checks + msg::semantically_valid). The support test checks that for
// every type in RGNAV_FOR_EACH_TYPE, so a new .lcm type without a factory fails to link.
#pragma once

#include <cstdint>

#include "rgnav_validators.hpp"

namespace rgnav::testing {

template <class T>
T sample(uint32_t variant = 0);

#define RGNAV_TESTING_DECLARE_SAMPLE(T) template <> T sample<T>(uint32_t variant);
RGNAV_FOR_EACH_TYPE(RGNAV_TESTING_DECLARE_SAMPLE)
#undef RGNAV_TESTING_DECLARE_SAMPLE

// A laser scan like the SICK LMS 2xx's: `beams` beams (181 or 361) over 180 deg.
laser_scan_t sample_laser_scan(int64_t scan_id, int beams, uint32_t variant = 0);

// A raw image of width x height with pixel_format image_t::FORMAT_GRAY8 or FORMAT_BGR8, rows
// padded to `row_stride` (0: tightly packed), filled with a deterministic pattern.
image_t sample_image(int width, int height, int32_t pixel_format, int row_stride = 0,
                     uint32_t variant = 0);

// A stereo pair of two such images.
stereo_images_t sample_stereo(int64_t frame_id, int width, int height, int32_t pixel_format);

}  // namespace rgnav::testing
