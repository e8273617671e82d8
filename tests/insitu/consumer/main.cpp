// Renders one hexahedron through the installed library (one process, no MPI) and writes a PNG.
#include <shellmarch/insitu.h>

#include <cstdio>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const double points[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
  const long long hexahedron[] = {0, 1, 2, 3, 4, 5, 6, 7};  // VTK order, the caller's id type
  try {
    shellmarch::insitu::Renderer vis;
    shellmarch::insitu::MeshView mesh;
    mesh.points = points;
    mesh.hexahedra = hexahedron;
    vis.setMesh(mesh);
    vis.setField("t", std::vector<float>{0, 1, 2, 3, 4, 5, 6, 7});
    shellmarch::insitu::RenderSettings s;
    s.width = s.height = 16;
    shellmarch::insitu::Image img = vis.render(s);
    const float centreAlpha = img.rgba[(8 * 16 + 8) * 4 + 3];
    img.writePng(argv[1]);
    const shellmarch::insitu::Stats st = vis.stats();
    std::printf("consumer: centre opacity %.3f, %llu validation errors, device %s\n", centreAlpha,
                (unsigned long long)st.validationErrors, st.deviceName.c_str());
    return centreAlpha > 0.05f && st.validationErrors == 0 ? 0 : 1;
  } catch (const shellmarch::insitu::Error& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
}
