// Fuzz target: io::parse_scene (TOML syntax through toml++, then every table, key, type, range and
// consistency check of the scene format) on arbitrary bytes. Every std::exception is an accepted
// outcome (a SceneError naming the line); a crash, a sanitizer report, a hang or a leak is a
// finding (validation/fuzz/README.md).
#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <string_view>

#include "io/scene_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // A fixed path: it only names the file in messages and anchors relative paths; parse_scene reads
  // no other file.
  static const std::filesystem::path path = "fuzz/scene.toml";
  try {
    (void)isomuscle::io::parse_scene(std::string_view(reinterpret_cast<const char*>(data), size),
                                     path);
  } catch (const std::exception&) {
    // a clear error for a bad scene: accepted
  }
  return 0;
}
