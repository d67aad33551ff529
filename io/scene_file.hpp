// Scene files (HDF5, layout in docs/formats.md): everything a Scene holds, stored exactly, so a scene
// prepared once (exported from Houdini, generated, edited in Python) runs the same anywhere.
#pragma once
#include "scene/scene.hpp"

#include <string>
#include <vector>

namespace weft::io {

inline constexpr const char* kSceneFormat = "weft-scene";
inline constexpr int kSceneFormatVersion = 1;

// Validates the scene (InputError), then writes it under a temporary name renamed into place when complete;
// I/O failures throw std::runtime_error naming the file.
void write_scene(const Scene& scene, const std::string& path);

// Reads a scene file and validates it. FormatError names the file and the dataset or attribute (not HDF5,
// wrong kind or version, missing dataset, wrong shape); validation errors are prefixed by the file name.
Scene read_scene(const std::string& path);

namespace h5 {
class File;
}
// Every SolverSettings field as an attribute of `group` (scene and cache files both hold one).
void write_settings(const h5::File& f, const std::string& group, const SolverSettings& s);
SolverSettings read_settings(const h5::File& f, const std::string& group);
// The names of the fields that differ (reals compared bit for bit), in the order the file lists them.
std::vector<std::string> differing_settings(const SolverSettings& a, const SolverSettings& b);

}  // namespace weft::io
