// ParaView particle snapshots of a crystal run (crystal/vtk.hpp): .vtp files and their .pvd collection.
#include "crystal/vtk.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "crystal/simulation.hpp"

namespace granwave::crystal {

VtkSeries::VtkSeries(std::string base) : base_(std::move(base)) {}

namespace {
void array(std::ofstream& f, const char* name, int components, std::size_t n, auto value) {
  f << "        <DataArray type=\"Float64\" Name=\"" << name << "\" NumberOfComponents=\"" << components
    << "\" format=\"ascii\">\n";
  for (std::size_t p = 0; p < n; ++p) {
    f << "         ";
    for (int k = 0; k < components; ++k) f << ' ' << value(p, k);
    f << '\n';
  }
  f << "        </DataArray>\n";
}
}  // namespace

void VtkSeries::write(const Dynamics& dyn) {
  char suffix[32];
  std::snprintf(suffix, sizeof suffix, "_%06zu.vtp", files_.size());
  const std::string path = base_ + suffix;
  std::ofstream f(path);
  if (!f) throw RunError("cannot write " + path);
  f.precision(10);
  const std::size_t n = dyn.size();
  std::vector<double> zz, zx, stress;
  layer_stress(dyn, zz, zx, &stress);
  f << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    << "  <PolyData>\n    <Piece NumberOfPoints=\"" << n << "\" NumberOfVerts=\"0\" NumberOfLines=\"0\""
    << " NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n      <Points>\n";
  array(f, "position", 3, n, [&](std::size_t p, int k) { return k == 0 ? dyn.x[p] : k == 1 ? dyn.y[p] : dyn.z[p]; });
  f << "      </Points>\n      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n";
  array(f, "radius", 1, n, [&](std::size_t p, int) { return dyn.radius[p]; });
  array(f, "velocity", 3, n, [&](std::size_t p, int k) { return k == 0 ? dyn.vx[p] : k == 1 ? dyn.vy[p] : dyn.vz[p]; });
  array(f, "angular_velocity", 3, n,
        [&](std::size_t p, int k) { return k == 0 ? dyn.wx[p] : k == 1 ? dyn.wy[p] : dyn.wz[p]; });
  array(f, "displacement", 3, n, [&](std::size_t p, int k) {
    return k == 0 ? dyn.x[p] - dyn.x0[p] : k == 1 ? dyn.y[p] - dyn.y0[p] : dyn.z[p] - dyn.z0[p];
  });
  array(f, "stress", 9, n, [&](std::size_t p, int k) { return stress[9 * p + k]; });
  array(f, "fixed", 1, n, [&](std::size_t p, int) { return static_cast<double>(dyn.packing().fixed[p]); });
  array(f, "layer", 1, n, [&](std::size_t p, int) { return static_cast<double>(dyn.packing().layer[p]); });
  f << "      </PointData>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
  if (!f) throw RunError("cannot write " + path);
  files_.push_back(path);
  times_.push_back(dyn.time);
}

void VtkSeries::finish() {
  const std::string path = collection_path();
  std::ofstream f(path);
  if (!f) throw RunError("cannot write " + path);
  f.precision(12);
  f << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
  for (std::size_t k = 0; k < files_.size(); ++k)
    f << "    <DataSet timestep=\"" << times_[k] << "\" part=\"0\" file=\""
      << std::filesystem::path(files_[k]).filename().string() << "\"/>\n";
  f << "  </Collection>\n</VTKFile>\n";
}

}  // namespace granwave::crystal
