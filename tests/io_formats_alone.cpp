// weft::io_formats on its own (docs/library.md): linked with it and weft::solver only, without HDF5 or
// cairo, this program reads a JSON scene with an OBJ mesh and writes its cloth as .geo and .bgeo and reads it
// back.   io_formats_alone SCENE.json SCRATCH_DIR
#include "io/houdini_geo.hpp"
#include "io/json_scene.hpp"

#include <cstdio>
#include <exception>
#include <string>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: io_formats_alone SCENE.json SCRATCH_DIR\n");
    return 2;
  }
  try {
    const weft::Scene scene = weft::io::read_json_scene(argv[1]);
    weft::io::Geometry cloth = weft::io::from_trimesh({scene.points.position, scene.triangles});
    cloth.position_storage = weft::io::Storage::Float64;  // exact positions back
    for (const std::string ext : {"geo", "bgeo"}) {
      const std::string path = std::string(argv[2]) + "/io_formats_alone." + ext;
      ext == "geo" ? weft::io::write_geo(cloth, path) : weft::io::write_bgeo(cloth, path);
      const weft::io::TriMesh back = weft::io::to_trimesh(weft::io::read_geo(path));
      if (back.positions != scene.points.position || back.triangles != scene.triangles) {
        std::fprintf(stderr, "io_formats_alone: %s differs from the scene's cloth\n", path.c_str());
        return 1;
      }
    }
    std::printf("io_formats alone: %zu points, %zu triangles through .geo and .bgeo\n", scene.points.size(),
                scene.triangles.size());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "io_formats_alone: %s\n", e.what());
    return 1;
  }
}
