// Structured quad mesh of the scene handed to gmsh as discrete entities and written as MSH 4.1.
// The blocks are rectangles, so the transfinite mesh is the tensor product of the SceneLayout
// grid lines; building it directly (instead of gmsh transfinite curves, one geometric progression
// per curve) lets one line carry the h_max cap, the grading and interior breakpoints at once.
#include "geometry/scene_mesh.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <gmsh.h>
#include <ostream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <unistd.h>
#include <vector>

#include "geometry/gmsh_session.h"
#include "geometry/graded_spacing.h"
#include "geometry/scene_ids.h"
#include "geometry/scene_layout.h"

namespace kimp::geometry
{
  namespace
  {
    // gmsh element types: 2-node line, 4-node quadrangle.
    constexpr int gmsh_line = 1;
    constexpr int gmsh_quad = 3;

    // Discrete curve entities; each carries exactly one physical group (deal.II reads one).
    enum CurveEntity : int
    {
      wall_base_curve  = 1,
      soil_base_curve  = 2,
      soil_side_curve  = 3,
      slab_front_curve = 4,
      wall_front_curve = 5,
      wall_back_curve  = 6,
      soil_front_curve = 7
    };

    // One structured block: node tag of grid point (i, j) is tags[j * x.size() + i].
    struct Block
    {
      MaterialId               material;
      std::vector<double>      x, y;
      std::vector<std::size_t> tags;

      std::size_t tag(std::size_t i, std::size_t j) const { return tags[j * x.size() + i]; }
      std::size_t n_cells() const { return (x.size() - 1) * (y.size() - 1); }
    };

    // Nodes owned (classified) by one surface entity.
    struct SurfaceNodes
    {
      std::vector<std::size_t> tags;
      std::vector<double>      xyz;
    };

    // Numbers the nodes of a block; nodes of column 0 may be taken from a neighbour (shared).
    SurfaceNodes
    number_nodes(Block &block, std::size_t &next_tag, const std::vector<std::size_t> *shared_column)
    {
      SurfaceNodes owned;
      block.tags.resize(block.x.size() * block.y.size());
      for (std::size_t j = 0; j < block.y.size(); ++j)
        for (std::size_t i = 0; i < block.x.size(); ++i)
        {
          std::size_t &tag = block.tags[j * block.x.size() + i];
          if (i == 0 && shared_column != nullptr)
          {
            tag = (*shared_column)[j];
            continue;
          }
          tag = next_tag++;
          owned.tags.push_back(tag);
          owned.xyz.insert(owned.xyz.end(), {block.x[i], block.y[j], 0.0});
        }
      return owned;
    }

    // Counter-clockwise connectivity (gmsh and deal.II both expect a positive orientation).
    std::vector<std::size_t> quad_connectivity(const Block &block)
    {
      std::vector<std::size_t> nodes;
      nodes.reserve(4 * block.n_cells());
      for (std::size_t j = 0; j + 1 < block.y.size(); ++j)
        for (std::size_t i = 0; i + 1 < block.x.size(); ++i)
          nodes.insert(
            nodes.end(),
            {block.tag(i, j), block.tag(i + 1, j), block.tag(i + 1, j + 1), block.tag(i, j + 1)});
      return nodes;
    }

    std::vector<std::size_t> row_lines(const Block &block, std::size_t j)
    {
      std::vector<std::size_t> nodes;
      for (std::size_t i = 0; i + 1 < block.x.size(); ++i)
        nodes.insert(nodes.end(), {block.tag(i, j), block.tag(i + 1, j)});
      return nodes;
    }

    std::vector<std::size_t> column_lines(const Block &block, std::size_t i)
    {
      std::vector<std::size_t> nodes;
      for (std::size_t j = 0; j + 1 < block.y.size(); ++j)
        nodes.insert(nodes.end(), {block.tag(i, j), block.tag(i, j + 1)});
      return nodes;
    }

    // Sine of the smallest corner angle of the rectangle-or-not quad with corners p[0..3].
    double scaled_jacobian(const std::array<std::array<double, 2>, 4> &p)
    {
      double result = 1.0;
      for (int k = 0; k < 4; ++k)
      {
        const auto  &a     = p[(k + 3) % 4];
        const auto  &b     = p[k];
        const auto  &c     = p[(k + 1) % 4];
        const double ux    = c[0] - b[0];
        const double uy    = c[1] - b[1];
        const double vx    = a[0] - b[0];
        const double vy    = a[1] - b[1];
        const double cross = ux * vy - uy * vx;
        result             = std::min(result, cross / (std::hypot(ux, uy) * std::hypot(vx, vy)));
      }
      return result;
    }

    void add_block_statistics(const Block &block, MeshStatistics &statistics)
    {
      for (std::size_t j = 0; j + 1 < block.y.size(); ++j)
        for (std::size_t i = 0; i + 1 < block.x.size(); ++i)
        {
          const double dx          = block.x[i + 1] - block.x[i];
          const double dy          = block.y[j + 1] - block.y[j];
          statistics.min_cell_size = std::min({statistics.min_cell_size, dx, dy});
          statistics.max_cell_size = std::max({statistics.max_cell_size, dx, dy});
          statistics.max_aspect_ratio =
            std::max(statistics.max_aspect_ratio, std::max(dx, dy) / std::min(dx, dy));
          const std::array<std::array<double, 2>, 4> corners{{{block.x[i], block.y[j]},
                                                              {block.x[i + 1], block.y[j]},
                                                              {block.x[i + 1], block.y[j + 1]},
                                                              {block.x[i], block.y[j + 1]}}};
          statistics.min_scaled_jacobian =
            std::min(statistics.min_scaled_jacobian, scaled_jacobian(corners));
        }
    }

    // Longest edge of the cells of column i whose y range lies in [y_low, y_high].
    double column_cell_size(const Block &block, std::size_t i, double y_low, double y_high)
    {
      double size = 0.0;
      for (std::size_t j = 0; j + 1 < block.y.size(); ++j)
        if (block.y[j] >= y_low && block.y[j + 1] <= y_high)
          size = std::max({size, block.x[i + 1] - block.x[i], block.y[j + 1] - block.y[j]});
      return size;
    }

    void add_surface(int                 tag,
                     const SurfaceNodes &nodes,
                     const Block        &block,
                     std::size_t        &next_element,
                     const std::string  &name)
    {
      gmsh::model::addDiscreteEntity(2, tag);
      gmsh::model::mesh::addNodes(2, tag, nodes.tags, nodes.xyz);
      const std::vector<std::size_t> connectivity = quad_connectivity(block);
      std::vector<std::size_t>       elements(connectivity.size() / 4);
      for (std::size_t &e : elements)
        e = next_element++;
      gmsh::model::mesh::addElementsByType(tag, gmsh_quad, elements, connectivity);
      gmsh::model::addPhysicalGroup(2, {tag}, block.material);
      gmsh::model::setPhysicalName(2, block.material, name);
    }

    void add_curve(int curve, const std::vector<std::size_t> &line_nodes, std::size_t &next_element)
    {
      gmsh::model::addDiscreteEntity(1, curve);
      std::vector<std::size_t> elements(line_nodes.size() / 2);
      for (std::size_t &e : elements)
        e = next_element++;
      gmsh::model::mesh::addElementsByType(curve, gmsh_line, elements, line_nodes);
    }

    void add_boundary_group(BoundaryId id, const std::vector<int> &curves, const std::string &name)
    {
      gmsh::model::addPhysicalGroup(1, curves, id);
      gmsh::model::setPhysicalName(1, id, name);
    }

    /// Whether `file` ends with a complete MSH section (its last line is "$End<section>").
    bool ends_with_section_end(const std::filesystem::path &file)
    {
      std::ifstream in(file, std::ios::binary | std::ios::ate);
      if (!in)
        return false;
      const std::streamoff size = in.tellg();
      const std::streamoff tail = std::min<std::streamoff>(size, 256);
      std::string          text(static_cast<std::size_t>(tail), '\0');
      in.seekg(size - tail);
      in.read(text.data(), tail);
      while (!text.empty() && (text.back() == '\n' || text.back() == '\r'))
        text.pop_back();
      const std::size_t line = text.rfind('\n');
      return in && text.compare(line == std::string::npos ? 0 : line + 1, 4, "$End") == 0;
    }

    /// gmsh reports no write error (a full disk leaves a short or empty file): `file` must end
    /// with a section end and reach the disk.
    void check_written(const std::filesystem::path &file)
    {
      const int fd         = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
      const int sync_error = fd < 0 ? errno : (::fsync(fd) == 0 ? 0 : errno);
      if (fd >= 0)
        ::close(fd);
      if (sync_error != 0 || !ends_with_section_end(file))
        throw std::runtime_error("build_scene_mesh: could not write the mesh file '" +
                                 file.string() + "': " +
                                 (sync_error != 0 ? std::strerror(sync_error) :
                                                    "the file gmsh wrote is incomplete (disk "
                                                    "full?)"));
    }
  } // namespace


  std::ostream &operator<<(std::ostream &out, const MeshStatistics &s)
  {
    // Lengths and ratios with 4 significant figures (a log line, not data).
    const std::streamsize precision = out.precision(4);
    out << s.n_nodes << " nodes, " << s.n_cells << " quads (slab " << s.n_slab_cells << ", wall "
        << s.n_wall_cells << ", soil " << s.n_soil_cells << "), contact faces slab "
        << s.n_slab_contact_faces << " / wall " << s.n_wall_contact_faces << ", cell size "
        << s.min_cell_size << " to " << s.max_cell_size << " m (contact " << s.contact_cell_size
        << " m), neighbour ratio <= " << s.max_neighbour_ratio
        << ", aspect ratio <= " << s.max_aspect_ratio << ", min scaled Jacobian "
        << s.min_scaled_jacobian;
    out.precision(precision);
    return out;
  }


  namespace
  {
    /** Counts, cell sizes, neighbour and aspect ratios of the blocks that are meshed. */
    MeshStatistics block_statistics(const SceneGeometry &geometry,
                                    const Block         &wall,
                                    const Block         &soil,
                                    const Block         &slab,
                                    std::size_t          n_nodes)
    {
      MeshStatistics statistics;
      statistics.n_nodes      = n_nodes;
      statistics.n_wall_cells = wall.n_cells();
      statistics.n_soil_cells = geometry.with_backfill ? soil.n_cells() : 0;
      statistics.n_slab_cells = geometry.mesh_slab ? slab.n_cells() : 0;
      statistics.n_cells =
        statistics.n_wall_cells + statistics.n_soil_cells + statistics.n_slab_cells;
      statistics.n_wall_contact_faces = wall.y.size() - 1;
      statistics.n_slab_contact_faces = geometry.mesh_slab ? slab.y.size() - 1 : 0;
      statistics.min_cell_size        = HUGE_VAL;
      add_block_statistics(wall, statistics);
      if (geometry.with_backfill)
        add_block_statistics(soil, statistics);
      if (geometry.mesh_slab)
        add_block_statistics(slab, statistics);

      std::vector<double> wall_soil_x = wall.x;
      if (geometry.with_backfill)
        wall_soil_x.insert(wall_soil_x.end(), soil.x.begin() + 1, soil.x.end());
      statistics.max_neighbour_ratio =
        std::max(max_neighbour_ratio(wall_soil_x), max_neighbour_ratio(wall.y));
      if (geometry.mesh_slab)
        statistics.max_neighbour_ratio = std::max({statistics.max_neighbour_ratio,
                                                   max_neighbour_ratio(slab.x),
                                                   max_neighbour_ratio(slab.y)});

      statistics.contact_cell_size =
        column_cell_size(wall, 0, geometry.slab_bottom(), geometry.resolved_slab_top());
      if (geometry.mesh_slab)
        statistics.contact_cell_size =
          std::max(statistics.contact_cell_size,
                   column_cell_size(slab, slab.x.size() - 2, -HUGE_VAL, HUGE_VAL));
      return statistics;
    }

    /** The surfaces, the boundary curves and their physical groups, written to @p msh_file. */
    void write_scene_msh(const SceneGeometry         &geometry,
                         const std::filesystem::path &msh_file,
                         const Block                 &wall,
                         const Block                 &soil,
                         const Block                 &slab,
                         const SurfaceNodes          &wall_nodes,
                         const SurfaceNodes          &soil_nodes,
                         const SurfaceNodes          &slab_nodes)
    {
      // gmsh 4.8 reports some failures by throwing non-std types (int): translate them.
      try
      {
        GmshSession session("kimp_scene");
        session.set_option("Mesh.MshFileVersion", 4.1);
        session.set_option("Mesh.Binary", 0);
        session.set_option("Mesh.SaveAll", 0);
        session.set_option("Mesh.SaveParametric", 0);

        std::size_t next_element = 1;
        if (geometry.mesh_slab)
          add_surface(slab_material, slab_nodes, slab, next_element, "slab");
        add_surface(wall_material, wall_nodes, wall, next_element, "wall");
        if (geometry.with_backfill)
          add_surface(soil_material, soil_nodes, soil, next_element, "soil");

        add_curve(wall_base_curve, row_lines(wall, 0), next_element);
        add_curve(wall_front_curve, column_lines(wall, 0), next_element);
        std::vector<int> base_curves{wall_base_curve};
        if (geometry.with_backfill)
        {
          add_curve(soil_base_curve, row_lines(soil, 0), next_element);
          add_curve(soil_side_curve, column_lines(soil, soil.x.size() - 1), next_element);
          base_curves.push_back(soil_base_curve);
          add_boundary_group(soil_far_side, {soil_side_curve}, "soil_far_side");
          if (geometry.interface_contact)
          {
            std::vector<std::size_t> back = column_lines(wall, wall.x.size() - 1);
            back.resize(2 * (soil.y.size() - 1)); // up to H_b; above it the wall back is free
            add_curve(wall_back_curve, back, next_element);
            add_curve(soil_front_curve, column_lines(soil, 0), next_element);
            add_boundary_group(wall_back, {wall_back_curve}, "wall_back");
            add_boundary_group(soil_front, {soil_front_curve}, "soil_front");
          }
        }
        add_boundary_group(fixed_base, base_curves, "fixed_base");
        if (geometry.mesh_slab)
        {
          add_curve(slab_front_curve, column_lines(slab, slab.x.size() - 1), next_element);
          add_boundary_group(slab_contact, {slab_front_curve}, "slab_contact");
        }
        add_boundary_group(wall_contact, {wall_front_curve}, "wall_contact");

        std::error_code error;
        if (msh_file.has_parent_path())
          std::filesystem::create_directories(msh_file.parent_path(), error);
        gmsh::write(msh_file.string());
        check_written(msh_file);
      }
      catch (const std::exception &)
      {
        throw;
      }
      catch (...)
      {
        throw std::runtime_error("build_scene_mesh: gmsh failed while writing '" +
                                 msh_file.string() + "'");
      }
    }
  } // namespace

  MeshStatistics build_scene_mesh(const SceneGeometry         &geometry,
                                  const std::filesystem::path &msh_file)
  {
    const SceneLayout layout = SceneLayout::build(geometry);

    Block wall{wall_material, layout.wall_x, layout.wall_y, {}};
    Block soil{soil_material, layout.soil_x, layout.soil_y, {}};
    Block slab{slab_material, layout.slab_x, layout.slab_y, {}};

    std::size_t        next_node  = 1;
    const SurfaceNodes wall_nodes = number_nodes(wall, next_node, nullptr);
    SurfaceNodes       soil_nodes, slab_nodes;
    if (geometry.with_backfill)
    {
      // The soil's first column is the wall's back column up to H_b: the bonded interface.
      std::vector<std::size_t> interface(soil.y.size());
      for (std::size_t j = 0; j < soil.y.size(); ++j)
        interface[j] = wall.tag(wall.x.size() - 1, j);
      // A contact interface: the soil gets its own nodes at the same places.
      soil_nodes = number_nodes(soil, next_node, geometry.interface_contact ? nullptr : &interface);
    }
    if (geometry.mesh_slab)
      slab_nodes = number_nodes(slab, next_node, nullptr);

    const MeshStatistics statistics = block_statistics(geometry, wall, soil, slab, next_node - 1);
    write_scene_msh(geometry, msh_file, wall, soil, slab, wall_nodes, soil_nodes, slab_nodes);
    return statistics;
  }
} // namespace kimp::geometry
