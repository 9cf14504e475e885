// `kimp mesh SCENE.yaml -o DIR`: the docs/physics.md §4 scene mesh of every wall height, with its
// statistics and PNG (scripts/plot_mesh.py) and VTU (deal.II GridIn + DataOut) previews.
#include "app/fem/mesh_run.h"

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <fstream>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string_view>
#include <unistd.h>

#include "app/fem/fem_common.h"
#include "app/fem/fem_scene.h"
#include "app/helper_programs.h"
#include "base/logging.h"
#include "fem/impact.h"
#include "geometry/scene_mesh.h"
#include "io/output_dir.h"
#include "io/summary.h"

extern char **environ;

namespace kimp::geometry
{
  // summary.json's "statistics" of a mesh: every member under its own name.
  NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(MeshStatistics,
                                     n_nodes,
                                     n_cells,
                                     n_slab_cells,
                                     n_wall_cells,
                                     n_soil_cells,
                                     n_slab_contact_faces,
                                     n_wall_contact_faces,
                                     min_cell_size,
                                     max_cell_size,
                                     contact_cell_size,
                                     max_neighbour_ratio,
                                     max_aspect_ratio,
                                     min_scaled_jacobian)
} // namespace kimp::geometry

namespace kimp::app
{
  using namespace kimp::base;
  using namespace kimp::io;
  namespace
  {
    constexpr const char *python = "/usr/bin/python3";

    /// Why a PNG preview cannot be drawn here, or "" if it can.
    std::string png_unavailable_reason(const std::filesystem::path &script)
    {
      if (script.empty())
        return "scripts/plot_mesh.py not found (set KIMP_DATA_DIR to the kimp source tree)";
      if (run_program({python, "-c", "import matplotlib, numpy"}, ProgramOutput::discard) != 0)
        return std::string(python) + " with matplotlib and numpy is not available "
                                     "(Debian: python3-matplotlib)";
      return "";
    }

    /// The last bytes of every PNG file: the IEND chunk (length 0, type, CRC).
    constexpr std::string_view png_end{"\0\0\0\0IEND\xae\x42\x60\x82", 12};

    /**
     * A file written by a writer that does not report write errors (deal.II's VTU writer
     * through an ofstream, matplotlib in a child process) is synced to disk and must end with
     * `end` (after trailing line breaks if `text`): a full disk leaves it short.
     * @throws OutputError naming the file.
     */
    void check_complete(const std::filesystem::path &file, std::string_view end, bool text)
    {
      const int fd         = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
      const int sync_error = fd < 0 ? errno : (::fsync(fd) == 0 ? 0 : errno);
      if (fd >= 0)
        ::close(fd);
      if (sync_error != 0)
        throw OutputError(fmt::format("'{}': {}", file.string(), std::strerror(sync_error)));
      std::ifstream        in(file, std::ios::binary | std::ios::ate);
      const std::streamoff size = in ? static_cast<std::streamoff>(in.tellg()) : 0;
      std::string          tail(static_cast<std::size_t>(std::min<std::streamoff>(size, 64)), '\0');
      in.seekg(size - static_cast<std::streamoff>(tail.size()));
      in.read(tail.data(), static_cast<std::streamsize>(tail.size()));
      while (text && !tail.empty() && (tail.back() == '\n' || tail.back() == '\r'))
        tail.pop_back();
      if (!in || tail.size() < end.size() ||
          tail.compare(tail.size() - end.size(), end.size(), end) != 0)
        throw OutputError(fmt::format("'{}' is incomplete (is the disk full?)", file.string()));
    }
  } // namespace

  void run_mesh(const LoadedScene<FemScene> &loaded, const OutputDir &output)
  {
    const auto start           = std::chrono::steady_clock::now();
    int        mpi_initialized = 0;
    MPI_Initialized(&mpi_initialized);
    int rank = 0;
    if (mpi_initialized)
      MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank != 0)
      return;

    const FemScene             &scene  = loaded.scene;
    const std::filesystem::path script = find_helper_script("plot_mesh.py");
    const std::string           no_png = png_unavailable_reason(script);
    if (!no_png.empty())
      logger().warn("PNG previews skipped: {}", no_png);

    nlohmann::ordered_json cases = nlohmann::ordered_json::array();
    for (const double height : scene.wall_heights)
    {
      const std::string              name                = fem_case_name(height);
      const std::filesystem::path    msh                 = output.file("mesh/" + name + ".msh");
      const std::filesystem::path    vtu                 = output.file("mesh/" + name + ".vtu");
      const geometry::SceneGeometry  geometry_parameters = scene_geometry(scene, height);
      const geometry::MeshStatistics statistics = write_scene_mesh(geometry_parameters, msh);
      std::ostringstream             statistics_text;
      statistics_text << statistics;
      logger().info("{}: {} ({})", name, msh.string(), statistics_text.str());

      fem::MeshInfo info;
      try
      {
        TemporaryFile temporary(vtu);
        info = fem::read_mesh_info(msh, temporary.path());
        check_complete(temporary.path(), "</VTKFile>", true);
        temporary.commit();
      }
      catch (const std::exception &error)
      {
        throw OutputError(
          fmt::format("{}: VTU preview of '{}': {}", name, msh.string(), error_message(error)));
      }
      logger().info("{}: deal.II reads {} cells, {} vertices; VTU preview {}",
                    name,
                    info.n_cells,
                    info.n_vertices,
                    vtu.string());

      nlohmann::ordered_json entry;
      entry["name"]        = name;
      entry["status"]      = "ok"; // a mesh that fails ends the command
      entry["wall_height"] = height;
      entry["mesh_file"]   = "mesh/" + name + ".msh";
      entry["vtu_preview"] = "mesh/" + name + ".vtu";
      entry["png_preview"] = nullptr;
      if (no_png.empty())
      {
        const std::filesystem::path png = output.file("mesh/" + name + ".png");
        TemporaryFile               temporary(png, true); // matplotlib reads the extension
        if (run_program({python, script.string(), msh.string(), "-o", temporary.path().string()},
                        ProgramOutput::errors) != 0)
          throw OutputError(fmt::format("{}: '{} {}' failed to draw '{}'",
                                        name,
                                        python,
                                        script.string(),
                                        png.string()));
        check_complete(temporary.path(), png_end, false);
        temporary.commit();
        logger().info("{}: PNG preview {}", name, png.string());
        entry["png_preview"] = "mesh/" + name + ".png";
      }
      entry["statistics"] = nlohmann::json(statistics);
      nlohmann::ordered_json areas;
      for (const auto &[id, area] : info.area_by_material)
        areas[std::to_string(id)] = area;
      entry["area_by_material"] = areas;
      cases.push_back(entry);
    }

    nlohmann::ordered_json summary = io::summary_preamble("mesh");
    summary["wall_time"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    summary["units"] = {{"lengths", "m"}, {"areas", "m^2 per metre of depth"}, {"wall_time", "s"}};
    summary["cases"] = cases;
    write_text_atomic(output.file("summary.json"), summary.dump(2) + "\n");
  }

  geometry::MeshStatistics write_scene_mesh(const geometry::SceneGeometry &geometry,
                                            const std::filesystem::path   &msh)
  {
    // gmsh writes the temporary name (its extension kept: gmsh chooses the format by it), which a
    // signal removes; commit() renames it and notes `msh` as written by the run.
    TemporaryFile                  temporary(msh, true);
    const geometry::MeshStatistics statistics =
      geometry::build_scene_mesh(geometry, temporary.path());
    temporary.commit();
    return statistics;
  }
} // namespace kimp::app
