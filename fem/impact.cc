// Plane-strain impact: M u_tt + f_int(u) = f_c(u, u_t), explicit leap-frog (lumped Gauss-Lobatto
// M) or Newmark average acceleration with semi-smooth Newton and a line search on the incremental
// potential (Belytschko et al., Nonlinear Finite Elements, 2014, §6.2-6.3; Wriggers, Computational
// Contact Mechanics, 2006); the low-rank contact tangent enters the factorized K + M / (beta dt^2)
// by the Woodbury identity (Hager, SIAM Review 31, 1989).
#include "fem/impact.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/vector_tools.h>

#include "fem/material_law.h"
#include "fem/penalty_contact.h"
#include "geometry/scene_ids.h"

namespace kimp::fem
{
  double p_wave_speed(const Material &m)
  {
    const double lambda =
      m.youngs_modulus * m.poisson_ratio / ((1 + m.poisson_ratio) * (1 - 2 * m.poisson_ratio));
    const double mu = m.youngs_modulus / (2 * (1 + m.poisson_ratio));
    return std::sqrt((lambda + 2 * mu) / m.density);
  }

  namespace
  {
    using namespace dealii;
    constexpr int dim = 2;
    using Vec         = TrilinosWrappers::MPI::Vector;

    /** Newmark average acceleration. */
    constexpr double newmark_beta  = 0.25;
    constexpr double newmark_gamma = 0.5;
    /** Largest implicit_max_halvings: time is counted in integer ticks of dt / 2^max. */
    constexpr unsigned int max_step_halvings = 30;
    /** Newton on the contact: relative residual tolerance. */
    constexpr double newton_tolerance = 1e-10;
    /** Residual accepted when Newton's direction is no longer a descent one (round-off). */
    constexpr double newton_roundoff_tolerance = 1e-8;
    /** Line search: iteration cap and the reduction of |dPi/dalpha| that ends it. */
    constexpr unsigned int max_line_search       = 20;
    constexpr double       line_search_reduction = 0.5;
    /** CG + AMG: relative residual reduction and iteration cap. */
    constexpr double       cg_tolerance      = 1e-12;
    constexpr unsigned int max_cg_iterations = 2000;
    /** Divergence guard: relative energy error beyond which the run is stopped. */
    constexpr double divergence_energy_error = 0.5;

    std::string fmt_double(double x)
    {
      std::ostringstream s;
      s.precision(6);
      s << x;
      return s.str();
    }

    void require(bool ok, const std::string &message)
    {
      AssertThrow(ok, ExcMessage(message));
    }

    /** One contact-face segment as gathered from all ranks (reference geometry, global DoFs). */
    struct FaceSegment
    {
      unsigned int                           boundary_id = 0;
      unsigned int                           material_id = 0;
      Point<dim>                             p0, p1, cell_center;
      std::array<types::global_dof_index, 4> dofs{}; // p0 x, p0 y, p1 x, p1 y
    };

    class ImpactProblem
    {
    public:
      ImpactProblem(const ImpactParameters &parameters, MPI_Comm comm, std::ostream *log);
      ImpactResult run();

    private:
      void validate_parameters() const;
      void make_grid();
      void setup_system();
      void setup_contact();
      void assemble_system();
      /** Constitutive law per material id: material_laws, else linear elastic. */
      void make_laws();
      /** f = internal force of u: K u for linear laws, else assembled from the laws' stress
       *  with the committed history (trial history written). */
      void internal_force(const Vec &u, Vec &f);
      void compute_time_step();
      void run_explicit();
      void run_implicit();

      /** Implicit: K + c1 M of one step size dt / 2^level and its solver. */
      struct StepOperator
      {
        double                                             dt = 0, c1 = 0;
        double                                             rigid_diagonal = 0; ///< m c1
        TrilinosWrappers::SparseMatrix                     base, system;
        SolverControl                                      control;
        std::unique_ptr<TrilinosWrappers::SolverDirect>    direct;
        std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg;
        /** Direct only: columns of the compact block of base^{-1}, computed on first use. */
        std::vector<std::vector<double>> flexibility;
      };
      StepOperator &step_operator(unsigned int level);
      /** x = base^{-1} b (direct solver only). */
      void                       base_solve(StepOperator &op, Vec &x, const Vec &b);
      const std::vector<double> &flexibility_column(StepOperator &op, unsigned int k);
      /** Newton increment (du, du_r) of J (du, du_r) = -(residual, r_rigid). */
      void solve_newton_system(StepOperator                     &op,
                               const PenaltyContact::Evaluation &ev,
                               const Vec                        &residual,
                               double                            r_rigid,
                               Vec                              &du,
                               double                           &du_r);

      /** Compact contact values (all ranks) of a distributed vector, plus the rigid DoF. */
      std::vector<double> gather_compact(const Vec &v, double rigid_value) const;
      /** Two compact gathers in one reduction: (a, rigid a), (b, rigid b). */
      std::pair<std::vector<double>, std::vector<double>>
      gather_compact(const Vec &a, double rigid_a, const Vec &b, double rigid_b) const;
      /** Adds compact contact forces to the owned entries of a distributed vector. */
      void scatter_add(const std::vector<double> &compact, Vec &f) const;
      /** Records histories and energies of step n (time t). */
      void              record(unsigned long                     n,
                               double                            t,
                               const Vec                        &u,
                               const Vec                        &v_n,
                               const Vec                        &Ku,
                               double                            u_r,
                               double                            v_r,
                               const PenaltyContact::Evaluation &ev,
                               const std::vector<double>        &cu);
      [[noreturn]] void throw_divergence(unsigned long n, double t, const Vec &u) const;
      void              output_results(double                     t,
                                       const Vec                 &u,
                                       const Vec                 &v,
                                       const std::vector<double> &contact_force);
      void              finish(ImpactResult &result, double wall_seconds);
      void              log_line(const std::string &s) const;

      const ImpactParameters                    prm;
      MPI_Comm                                  comm;
      std::ostream                             *log;
      parallel::distributed::Triangulation<dim> triangulation;
      FESystem<dim>                             fe;
      DoFHandler<dim>                           dof_handler;
      IndexSet                                  locally_owned, locally_relevant;
      AffineConstraints<double>                 constraints;
      TrilinosWrappers::SparseMatrix            stiffness;
      Vec                                       mass, inverse_mass, slab_mass_x, free_mask;
      double                                    slab_total_mass = 0;

      std::unique_ptr<PenaltyContact>      contact;
      std::vector<types::global_dof_index> contact_dofs; // compact node component -> global DoF
      std::vector<double>                  wall_weight, front_weight; // compact node weights
      double                               initial_gap = 0;
      double contact_width = 0, contact_wave_speed = 0; // slave face length (m), wall c_p (m/s)
      double omega_penalty = 0, omega_mesh = 0;
      double dt = 0, dt_stable = 0;

      // Bookkeeping of the run.
      double                                      e0 = 0, contact_work = 0, damping_work = 0;
      std::vector<double>                         cu_prev, fc_prev;
      std::vector<double>                         raw_force; // every step
      unsigned long                               sample_every = 1;
      ImpactHistory                               history;
      double                                      max_energy_error = 0, max_penetration = 0;
      std::vector<std::pair<double, std::string>> pvd_records;
      unsigned long                               n_newton = 0, n_steps_done = 0;
      double                                      slab_v_end           = 0;
      bool                                        separated_flag       = false;
      double                                      penetration_integral = 0;
      std::map<unsigned int, std::unique_ptr<StepOperator>>      step_operators;
      std::vector<bool>                                          compact_free;
      std::map<unsigned int, std::shared_ptr<const MaterialLaw>> laws;
      bool                                                       linear_laws = true;
      QuadraturePointHistory                                     qp_history;
      Vec           u_ghosted, force_writable; // internal_force() of non-linear laws
      unsigned long n_linear_solves = 0, n_step_halvings = 0;
      double        linear_solver_seconds = 0, linear_setup_seconds = 0;
    };

    ImpactProblem::ImpactProblem(const ImpactParameters &parameters,
                                 MPI_Comm                comm_,
                                 std::ostream           *log_)
      : prm(parameters)
      , comm(comm_)
      , log(log_)
      , triangulation(comm_)
      , fe(FE_Q<dim>(1), dim)
      , dof_handler(triangulation)
    {
    }

    void ImpactProblem::log_line(const std::string &s) const
    {
      if (log != nullptr && Utilities::MPI::this_mpi_process(comm) == 0)
        *log << s << '\n';
    }

    void ImpactProblem::validate_parameters() const
    {
      require(std::filesystem::is_regular_file(prm.mesh_file),
              "mesh_file = '" + prm.mesh_file.string() + "' (must be an existing MSH file)");
      require(!prm.materials.empty(), "materials is empty (must give one per material id)");
      for (const auto &[id, m] : prm.materials)
      {
        const std::string key = "materials[" + std::to_string(id) + "].";
        require(m.youngs_modulus > 0,
                key + "youngs_modulus = " + fmt_double(m.youngs_modulus) + " Pa (must be > 0)");
        require(m.poisson_ratio >= 0 && m.poisson_ratio < 0.5,
                key + "poisson_ratio = " + fmt_double(m.poisson_ratio) + " (must be in [0, 0.5))");
        require(m.density > 0,
                key + "density = " + fmt_double(m.density) + " kg/m^3 (must be > 0)");
      }
      for (const auto &[id, law] : prm.material_laws)
        require(law != nullptr && prm.materials.count(id) > 0,
                "material_laws[" + std::to_string(id) +
                  "] (must be a law for a material id that has an entry in materials)");
      if (prm.rigid_slab)
      {
        require(prm.slab_mass > 0,
                "slab_mass = " + fmt_double(prm.slab_mass) +
                  " kg/m (must be > 0 for a rigid slab)");
        require(prm.slab_face_y1 > prm.slab_face_y0,
                "slab_face_y1 = " + fmt_double(prm.slab_face_y1) +
                  " m (must be > slab_face_y0 = " + fmt_double(prm.slab_face_y0) + " m)");
      }
      require(prm.initial_velocity > 0,
              "initial_velocity = " + fmt_double(prm.initial_velocity) + " m/s (must be > 0)");
      require(prm.penalty_factor > 0,
              "penalty_factor = " + fmt_double(prm.penalty_factor) + " (must be > 0)");
      require(prm.contact_damping_ratio >= 0 && prm.contact_damping_ratio <= 1,
              "contact_damping_ratio = " + fmt_double(prm.contact_damping_ratio) +
                " (must be in [0, 1])");
      require(prm.smoothing_window >= 0,
              "smoothing_window = " + fmt_double(prm.smoothing_window) + " s (must be >= 0)");
      require(prm.dt >= 0, "dt = " + fmt_double(prm.dt) + " s (must be >= 0; 0 = automatic)");
      require(prm.dt_over_limit >= 0 && (prm.dt_over_limit == 0 || prm.dt == 0),
              "dt_over_limit = " + fmt_double(prm.dt_over_limit) +
                " (must be >= 0, and dt must be 0 when it is used)");
      require(prm.cfl_safety > 0 && prm.cfl_safety <= 1,
              "cfl_safety = " + fmt_double(prm.cfl_safety) + " (must be in (0, 1])");
      require(prm.implicit_dt_factor > 0,
              "implicit_dt_factor = " + fmt_double(prm.implicit_dt_factor) + " (must be > 0)");
      require(prm.end_time > 0, "end_time = " + fmt_double(prm.end_time) + " s (must be > 0)");
      require(prm.separation_hold_time >= 0,
              "separation_hold_time = " + fmt_double(prm.separation_hold_time) +
                " s (must be >= 0)");
      require(prm.output_interval >= 0,
              "output_interval = " + fmt_double(prm.output_interval) + " s (must be >= 0)");
      require(prm.implicit_max_halvings <= max_step_halvings,
              "implicit_max_halvings = " + std::to_string(prm.implicit_max_halvings) +
                " (must be <= " + std::to_string(max_step_halvings) + ")");
      require(prm.implicit_newton_max_iterations > 0,
              "implicit_newton_max_iterations = " +
                std::to_string(prm.implicit_newton_max_iterations) + " (must be > 0)");
      require(prm.progress_interval > 0,
              "progress_interval = " + std::to_string(prm.progress_interval) +
                " steps (must be > 0)");
      require(prm.vtu_interval >= 0,
              "vtu_interval = " + fmt_double(prm.vtu_interval) + " s (must be >= 0)");
    }

    void ImpactProblem::make_grid()
    {
      Triangulation<dim> serial;
      {
        GridIn<dim> grid_in;
        grid_in.attach_triangulation(serial);
        std::ifstream in(prm.mesh_file);
        grid_in.read_msh(in);
      }
      for (const auto &cell : serial.active_cell_iterators())
        require(prm.materials.count(cell->material_id()) > 0,
                "mesh '" + prm.mesh_file.string() + "' has material id " +
                  std::to_string(cell->material_id()) + " (no entry in materials)");
      if (!prm.rigid_slab)
      {
        triangulation.copy_triangulation(serial);
        return;
      }
      // Rigid slab: drop the slab cells; boundary ids are restored from the face centres because
      // removing cells does not carry them over.
      std::map<std::pair<double, double>, types::boundary_id>     boundary_of;
      std::set<typename Triangulation<dim>::active_cell_iterator> slab_cells;
      for (const auto &cell : serial.active_cell_iterators())
      {
        if (cell->material_id() == geometry::slab_material)
          slab_cells.insert(cell);
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            boundary_of[{face->center()[0], face->center()[1]}] = face->boundary_id();
      }
      Triangulation<dim> reduced;
      if (slab_cells.empty())
        reduced.copy_triangulation(serial);
      else
        GridGenerator::create_triangulation_with_removed_cells(serial, slab_cells, reduced);
      for (const auto &cell : reduced.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
          {
            const auto it = boundary_of.find({face->center()[0], face->center()[1]});
            face->set_boundary_id(it == boundary_of.end() ? 0 : it->second);
          }
      triangulation.copy_triangulation(reduced);
    }

    void ImpactProblem::setup_system()
    {
      dof_handler.distribute_dofs(fe);
      locally_owned = dof_handler.locally_owned_dofs();
      DoFTools::extract_locally_relevant_dofs(dof_handler, locally_relevant);

      constraints.clear();
      constraints.reinit(locally_relevant);
      VectorTools::interpolate_boundary_values(dof_handler,
                                               geometry::fixed_base,
                                               Functions::ZeroFunction<dim>(dim),
                                               constraints);
      VectorTools::interpolate_boundary_values(dof_handler,
                                               geometry::soil_far_side,
                                               Functions::ZeroFunction<dim>(dim),
                                               constraints,
                                               ComponentMask(std::vector<bool>{true, false}));
      constraints.close();
    }

    void ImpactProblem::setup_contact()
    {
      // Gather every contact-face segment of the locally owned cells to all ranks.
      std::vector<double> local;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary() && (face->boundary_id() == geometry::slab_contact ||
                                        face->boundary_id() == geometry::wall_contact))
            {
              local.push_back(face->boundary_id());
              local.push_back(cell->material_id());
              for (unsigned int v = 0; v < 2; ++v)
                for (unsigned int d = 0; d < dim; ++d)
                  local.push_back(face->vertex(v)[d]);
              for (unsigned int d = 0; d < dim; ++d)
                local.push_back(cell->center()[d]);
              for (unsigned int v = 0; v < 2; ++v)
                for (unsigned int c = 0; c < dim; ++c)
                  local.push_back(static_cast<double>(face->vertex_dof_index(v, c)));
            }
      constexpr unsigned int   record = 12;
      std::vector<FaceSegment> segments;
      for (const auto &part : Utilities::MPI::all_gather(comm, local))
        for (std::size_t k = 0; k + record <= part.size(); k += record)
        {
          FaceSegment s;
          s.boundary_id = static_cast<unsigned int>(part[k]);
          s.material_id = static_cast<unsigned int>(part[k + 1]);
          s.p0          = Point<dim>(part[k + 2], part[k + 3]);
          s.p1          = Point<dim>(part[k + 4], part[k + 5]);
          s.cell_center = Point<dim>(part[k + 6], part[k + 7]);
          for (unsigned int i = 0; i < 4; ++i)
            s.dofs[i] = static_cast<types::global_dof_index>(part[k + 8 + i]);
          segments.push_back(s);
        }
      // Deterministic order independent of the partition: by coordinates.
      const auto key = [](const Point<dim> &p) { return std::make_pair(p[0], p[1]); };
      std::sort(segments.begin(),
                segments.end(),
                [&](const FaceSegment &a, const FaceSegment &b) {
                  return std::make_pair(key(a.p0), key(a.p1)) <
                         std::make_pair(key(b.p0), key(b.p1));
                });

      const unsigned int slave_id =
        prm.rigid_slab ? geometry::wall_contact : geometry::slab_contact;
      std::map<std::pair<double, double>, unsigned int>   node_of;
      std::vector<std::pair<double, double>>              keys;
      std::vector<unsigned int>                           node_boundary;
      std::vector<std::array<types::global_dof_index, 2>> node_dofs;
      for (const auto &s : segments)
      {
        if (prm.rigid_slab && s.boundary_id != geometry::wall_contact)
          continue;
        for (unsigned int v = 0; v < 2; ++v)
        {
          const auto k = key(v == 0 ? s.p0 : s.p1);
          if (node_of.count(k) == 0)
          {
            node_of[k] = 0;
            keys.push_back(k);
          }
        }
      }
      std::sort(keys.begin(), keys.end());
      for (unsigned int i = 0; i < keys.size(); ++i)
        node_of[keys[i]] = i;
      node_boundary.assign(keys.size(), 0);
      node_dofs.assign(keys.size(), {});
      double h_contact = std::numeric_limits<double>::max();
      for (const auto &s : segments)
      {
        if (prm.rigid_slab && s.boundary_id != geometry::wall_contact)
          continue;
        h_contact = std::min(h_contact, s.p0.distance(s.p1));
        for (unsigned int v = 0; v < 2; ++v)
        {
          const unsigned int i = node_of[key(v == 0 ? s.p0 : s.p1)];
          node_boundary[i]     = s.boundary_id;
          node_dofs[i]         = {{s.dofs[2 * v], s.dofs[2 * v + 1]}};
        }
      }
      require(!keys.empty(),
              "mesh '" + prm.mesh_file.string() + "' has no contact faces (boundary id " +
                std::to_string(static_cast<unsigned>(geometry::wall_contact)) + " must exist)");

      const unsigned int n_nodes = keys.size();
      contact_dofs.resize(2 * n_nodes);
      std::vector<PenaltyContact::Node> nodes(n_nodes);
      for (unsigned int i = 0; i < n_nodes; ++i)
      {
        nodes[i]                = {keys[i].first, keys[i].second};
        contact_dofs[2 * i]     = node_dofs[i][0];
        contact_dofs[2 * i + 1] = node_dofs[i][1];
      }

      // Tributary lengths of the slave nodes (clipped to the rigid face extent) and the wall
      // weights for the mean wall-face displacement.
      const double y_lo = prm.rigid_slab ? prm.slab_face_y0 : -std::numeric_limits<double>::max();
      const double y_hi = prm.rigid_slab ? prm.slab_face_y1 : std::numeric_limits<double>::max();
      std::vector<double> tributary(n_nodes, 0.0);
      double              e_master = 0, slave_y_min = std::numeric_limits<double>::max(),
             slave_y_max = -std::numeric_limits<double>::max();
      std::vector<PenaltyContact::Segment> master;
      for (const auto &s : segments)
      {
        if (prm.rigid_slab && s.boundary_id != geometry::wall_contact)
          continue;
        const unsigned int a = node_of[key(s.p0)], b = node_of[key(s.p1)];
        if (s.boundary_id == geometry::wall_contact)
        {
          e_master = std::max(e_master, prm.materials.at(s.material_id).youngs_modulus);
          contact_wave_speed =
            std::max(contact_wave_speed, p_wave_speed(prm.materials.at(s.material_id)));
          if (!prm.rigid_slab)
          {
            // Outward normal of the master cell: sign of (t_y, -t_x) . (face mid - cell centre).
            const Tensor<1, dim> t   = s.p1 - s.p0;
            const Tensor<1, dim> out = 0.5 * (s.p0 + s.p1) - s.cell_center;
            master.push_back({a, b, (t[1] * out[0] - t[0] * out[1]) > 0 ? 1.0 : -1.0});
          }
        }
        if (s.boundary_id != slave_id)
          continue;
        const Point<dim> mid = 0.5 * (s.p0 + s.p1);
        for (const auto &[node, p] : {std::make_pair(a, s.p0), std::make_pair(b, s.p1)})
        {
          // The half of the segment next to the node, clipped to [y_lo, y_hi] along y when the
          // face is not horizontal.
          const double full = p.distance(mid);
          const double lo = std::min(p[1], mid[1]), hi = std::max(p[1], mid[1]);
          double       frac = 1;
          if (hi > lo)
            frac = std::max(0.0, std::min(hi, y_hi) - std::max(lo, y_lo)) / (hi - lo);
          else if (p[1] < y_lo || p[1] > y_hi)
            frac = 0;
          tributary[node] += full * frac;
        }
      }
      require(e_master > 0, "mesh '" + prm.mesh_file.string() + "' has no wall contact faces");

      const double              penalty_per_length = prm.penalty_factor * e_master / h_contact;
      const std::vector<double> node_mass          = [&]
      {
        std::vector<double> m = gather_compact(mass, 0.0);
        m.pop_back();
        return m;
      }();
      std::vector<PenaltyContact::Slave> slaves;
      omega_penalty = 0;
      for (unsigned int i = 0; i < n_nodes; ++i)
      {
        if (node_boundary[i] != slave_id || tributary[i] <= 0)
          continue;
        const double k   = penalty_per_length * tributary[i];
        const double m_s = node_mass[2 * i];
        double       m_m = prm.slab_mass;
        if (!prm.rigid_slab)
        {
          // Master mass: the nearest master node in the reference configuration.
          double best = std::numeric_limits<double>::max();
          for (unsigned int j = 0; j < n_nodes; ++j)
            if (node_boundary[j] == geometry::wall_contact &&
                std::abs(keys[j].second - keys[i].second) < best)
            {
              best = std::abs(keys[j].second - keys[i].second);
              m_m  = node_mass[2 * j];
            }
        }
        require(m_s > 0 && m_m > 0,
                "contact node at (" + fmt_double(keys[i].first) + ", " +
                  fmt_double(keys[i].second) + ") has no mass");
        const double m_red = 1.0 / (1.0 / m_s + 1.0 / m_m);
        // Implicit: no contact damping. Newton needs a residual with few kinks; a dashpot adds a
        // jump at first touch and a clamp while separating, and Newmark needs no chatter control
        // for stability.
        const double xi = prm.integrator == ImpactParameters::Integrator::implicit_newmark ?
                            0.0 :
                            prm.contact_damping_ratio;
        const double c  = 2 * xi * std::sqrt(k * m_red);
        slaves.push_back({i, k, c});
        contact_width += tributary[i];
        omega_penalty = std::max(omega_penalty, std::sqrt(k / m_red));
        slave_y_min   = std::min(slave_y_min, keys[i].second);
        slave_y_max   = std::max(slave_y_max, keys[i].second);
      }
      require(!slaves.empty(),
              "no slave contact node found (elastic slab: boundary id " +
                std::to_string(static_cast<unsigned>(geometry::slab_contact)) +
                "; rigid slab: wall face within [slab_face_y0, slab_face_y1])");

      if (prm.rigid_slab)
        contact = std::make_unique<PenaltyContact>(nodes, slaves, prm.slab_front_x);
      else
        contact = std::make_unique<PenaltyContact>(nodes, slaves, master);

      // Initial gaps: an overlap (or a slave that sees no master) is refused.
      const std::vector<double> gaps = contact->reference_gaps();
      initial_gap                    = std::numeric_limits<double>::max();
      for (unsigned int s = 0; s < gaps.size(); ++s)
      {
        const auto &n = nodes[slaves[s].node];
        require(gaps[s] >= 0,
                "slab overlaps the wall: contact node at (" + fmt_double(n.x) + ", " +
                  fmt_double(n.y) + ") m has initial gap " + fmt_double(gaps[s]) +
                  " m (must be >= 0)");
        if (std::isfinite(gaps[s]))
          initial_gap = std::min(initial_gap, gaps[s]);
      }
      require(initial_gap < std::numeric_limits<double>::max(),
              "no slave contact node projects onto the wall face");

      // Weights for the mean wall-face and slab-front displacements (tributary lengths).
      wall_weight.assign(2 * n_nodes + 1, 0.0);
      front_weight.assign(2 * n_nodes + 1, 0.0);
      if (prm.rigid_slab)
      {
        front_weight[2 * n_nodes] = 1;
        for (const auto &s : slaves)
          wall_weight[2 * s.node] = tributary[s.node];
      }
      else
      {
        for (const auto &s : slaves)
          front_weight[2 * s.node] = tributary[s.node];
        for (const auto &s : segments)
          if (s.boundary_id == geometry::wall_contact)
          {
            const double lo = std::max(std::min(s.p0[1], s.p1[1]), slave_y_min);
            const double hi = std::min(std::max(s.p0[1], s.p1[1]), slave_y_max);
            if (hi > lo)
            {
              wall_weight[2 * node_of[key(s.p0)]] += 0.5 * (hi - lo);
              wall_weight[2 * node_of[key(s.p1)]] += 0.5 * (hi - lo);
            }
          }
      }
      for (auto *w : {&wall_weight, &front_weight})
      {
        double sum = 0;
        for (double x : *w)
          sum += x;
        if (sum > 0)
          for (double &x : *w)
            x /= sum;
      }
      log_line("contact: " + std::to_string(slaves.size()) + " slave nodes, " +
               std::to_string(master.size()) + " master segments" +
               (prm.rigid_slab ? " (rigid face)" : "") + ", k/l = " +
               fmt_double(penalty_per_length) + " N/m^2, h_contact = " + fmt_double(h_contact) +
               " m, initial gap = " + fmt_double(initial_gap) + " m");
    }

    void ImpactProblem::assemble_system()
    {
      DynamicSparsityPattern dsp(locally_relevant);
      DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, false);
      if (prm.integrator == ImpactParameters::Integrator::implicit_newmark)
        for (const auto i : contact_dofs)
          if (locally_relevant.is_element(i))
            for (const auto j : contact_dofs)
              dsp.add(i, j);
      SparsityTools::distribute_sparsity_pattern(dsp, locally_owned, comm, locally_relevant);
      stiffness.reinit(locally_owned, locally_owned, dsp, comm);

      Vec mass_w, slab_w;
      mass_w.reinit(locally_owned, locally_relevant, comm, true);
      slab_w.reinit(locally_owned, locally_relevant, comm, true);

      const QGauss<dim>        quadrature(2);
      const QGaussLobatto<dim> lobatto(2);
      FEValues<dim>            fe_values(fe, quadrature, update_gradients | update_JxW_values);
      FEValues<dim>            fe_mass(fe, lobatto, update_values | update_JxW_values);
      const unsigned int       n = fe.n_dofs_per_cell();
      FullMatrix<double>       cell_matrix(n, n);
      Vector<double>           cell_mass(n), cell_slab(n);
      std::vector<types::global_dof_index> dof_indices(n);
      const FEValuesExtractors::Vector     displacement(0);
      std::vector<std::array<double, 3>>   b(n);
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
        {
          const Material    &m   = prm.materials.at(cell->material_id());
          const MaterialLaw &law = *laws.at(cell->material_id());
          // K from the law's tangent in the virgin state (modified Newton for non-linear laws).
          std::vector<double> history(law.n_history());
          law.initial_history(history.data());
          const VoigtTangent d = law.tangent({{0, 0, 0}}, history.data());
          fe_values.reinit(cell);
          fe_mass.reinit(cell);
          cell_matrix = 0;
          cell_mass   = 0;
          cell_slab   = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
          {
            for (unsigned int i = 0; i < n; ++i)
            {
              const auto eps = fe_values[displacement].symmetric_gradient(i, q);
              b[i]           = {{eps[0][0], eps[1][1], 2 * eps[0][1]}};
            }
            for (unsigned int i = 0; i < n; ++i)
            {
              std::array<double, 3> db{};
              for (unsigned int r = 0; r < 3; ++r)
                for (unsigned int c = 0; c < 3; ++c)
                  db[c] += b[i][r] * d[3 * r + c];
              for (unsigned int j = 0; j < n; ++j)
                cell_matrix(i, j) +=
                  (db[0] * b[j][0] + db[1] * b[j][1] + db[2] * b[j][2]) * fe_values.JxW(q);
            }
          }
          // Gauss-Lobatto points are the vertices: the mass matrix is diagonal.
          for (unsigned int q = 0; q < lobatto.size(); ++q)
            for (unsigned int i = 0; i < n; ++i)
            {
              const double phi = fe_mass.shape_value(i, q);
              cell_mass(i) += m.density * phi * phi * fe_mass.JxW(q);
            }
          if (cell->material_id() == geometry::slab_material)
            for (unsigned int i = 0; i < n; ++i)
              if (fe.system_to_component_index(i).first == 0)
                cell_slab(i) = cell_mass(i);
          cell->get_dof_indices(dof_indices);
          constraints.distribute_local_to_global(cell_matrix, dof_indices, stiffness);
          mass_w.add(dof_indices, cell_mass);
          slab_w.add(dof_indices, cell_slab);
        }
      stiffness.compress(VectorOperation::add);
      mass_w.compress(VectorOperation::add);
      slab_w.compress(VectorOperation::add);
      mass.reinit(locally_owned, comm);
      slab_mass_x.reinit(locally_owned, comm);
      mass        = mass_w;
      slab_mass_x = slab_w;
      inverse_mass.reinit(locally_owned, comm);
      free_mask.reinit(locally_owned, comm);
      for (const auto i : locally_owned)
        if (!constraints.is_constrained(i) && mass(i) > 0)
        {
          inverse_mass(i) = 1.0 / mass(i);
          free_mask(i)    = 1.0;
        }
      inverse_mass.compress(VectorOperation::insert);
      free_mask.compress(VectorOperation::insert);
      slab_total_mass = prm.rigid_slab ? prm.slab_mass : slab_mass_x.l1_norm();
      require(slab_total_mass > 0,
              "mesh '" + prm.mesh_file.string() + "' has no slab cells (material id " +
                std::to_string(static_cast<unsigned>(geometry::slab_material)) +
                ") and rigid_slab is false");
    }

    void ImpactProblem::make_laws()
    {
      laws.clear();
      linear_laws           = true;
      unsigned int n_values = 0;
      for (const auto &[id, m] : prm.materials)
      {
        const auto it = prm.material_laws.find(id);
        laws[id] =
          it != prm.material_laws.end() ? it->second : std::make_shared<const LinearElasticLaw>(m);
        linear_laws = linear_laws && laws[id]->is_linear();
        n_values    = std::max(n_values, laws[id]->n_history());
      }
      if (linear_laws)
        return;
      qp_history.reinit(triangulation.n_active_cells(), QGauss<dim>(2).size(), n_values);
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          qp_history.initialize_cell(cell->active_cell_index(), *laws.at(cell->material_id()));
      u_ghosted.reinit(locally_owned, locally_relevant, comm);
      force_writable.reinit(locally_owned, locally_relevant, comm, true);
    }

    void ImpactProblem::internal_force(const Vec &u, Vec &f)
    {
      if (linear_laws)
      {
        stiffness.vmult(f, u);
        return;
      }
      // f = sum over cells of B^T sigma(eps(u), h) JxW (Gauss points of the stiffness).
      u_ghosted      = u;
      force_writable = 0;
      const QGauss<dim>  quadrature(2);
      FEValues<dim>      fe_values(fe, quadrature, update_gradients | update_JxW_values);
      const unsigned int n = fe.n_dofs_per_cell();
      Vector<double>     cell_force(n);
      std::vector<types::global_dof_index> dof_indices(n);
      const FEValuesExtractors::Vector     displacement(0);
      std::vector<SymmetricTensor<2, dim>> eps(quadrature.size());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
        {
          const MaterialLaw &law = *laws.at(cell->material_id());
          const unsigned int c   = cell->active_cell_index();
          fe_values.reinit(cell);
          fe_values[displacement].get_function_symmetric_gradients(u_ghosted, eps);
          cell_force = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
          {
            const VoigtStress sigma = law.stress({{eps[q][0][0], eps[q][1][1], 2 * eps[q][0][1]}},
                                                 qp_history.committed(c, q),
                                                 qp_history.trial(c, q));
            for (unsigned int i = 0; i < n; ++i)
            {
              const auto e = fe_values[displacement].symmetric_gradient(i, q);
              cell_force(i) += (sigma[0] * e[0][0] + sigma[1] * e[1][1] + 2 * sigma[2] * e[0][1]) *
                               fe_values.JxW(q);
            }
          }
          cell->get_dof_indices(dof_indices);
          constraints.distribute_local_to_global(cell_force, dof_indices, force_writable);
        }
      force_writable.compress(VectorOperation::add);
      f = force_writable;
    }

    void ImpactProblem::compute_time_step()
    {
      // Q1 with a lumped mass: the highest mode of a cell of smallest edge h is omega = 2 c_p / h
      // (exact in 1D); a contact spring adds omega_c^2 = k (1/m_s + 1/m_m) at its nodes. The
      // damped central-difference limit is dt = 2 / omega (sqrt(1 + xi^2) - xi) (Belytschko
      // et al. 2014, eq. 6.3.14) with xi the contact damping seen by the highest mode.
      double local_omega = 0;
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
        {
          double h = std::numeric_limits<double>::max();
          for (unsigned int l = 0; l < cell->n_lines(); ++l)
            h = std::min(h, cell->line(l)->diameter());
          local_omega =
            std::max(local_omega, 2 * p_wave_speed(prm.materials.at(cell->material_id())) / h);
        }
      omega_mesh         = Utilities::MPI::max(local_omega, comm);
      const double omega = std::sqrt(omega_mesh * omega_mesh + omega_penalty * omega_penalty);
      const double xi    = prm.contact_damping_ratio * omega_penalty / omega;
      dt_stable          = 2 / omega * (std::sqrt(1 + xi * xi) - xi);
      if (prm.integrator == ImpactParameters::Integrator::explicit_central_difference)
      {
        require(prm.dt <= dt_stable,
                "dt = " + fmt_double(prm.dt) + " s is above the explicit stability limit " +
                  fmt_double(dt_stable) + " s (mesh omega = " + fmt_double(omega_mesh) +
                  " rad/s, contact penalty omega = " + fmt_double(omega_penalty) + " rad/s)");
        dt = prm.dt > 0            ? prm.dt :
             prm.dt_over_limit > 0 ? prm.dt_over_limit * dt_stable :
                                     prm.cfl_safety * dt_stable;
      }
      else
        dt = prm.dt > 0 ? prm.dt : prm.implicit_dt_factor * dt_stable;
      sample_every = prm.output_interval > 0 ?
                       std::max<unsigned long>(1, std::lround(prm.output_interval / dt)) :
                       1;
    }

    std::vector<double> ImpactProblem::gather_compact(const Vec &v, double rigid_value) const
    {
      std::vector<double> local(contact_dofs.size() + 1, 0.0), all(contact_dofs.size() + 1);
      for (unsigned int k = 0; k < contact_dofs.size(); ++k)
        if (locally_owned.is_element(contact_dofs[k]))
          local[k] = v(contact_dofs[k]);
      // Exactly one rank owns each entry, the others add zeros: the sum is exact.
      const int ierr = MPI_Allreduce(local.data(),
                                     all.data(),
                                     static_cast<int>(local.size()),
                                     MPI_DOUBLE,
                                     MPI_SUM,
                                     comm);
      AssertThrowMPI(ierr);
      all.back() = rigid_value;
      return all;
    }

    std::pair<std::vector<double>, std::vector<double>>
    ImpactProblem::gather_compact(const Vec &a, double rigid_a, const Vec &b, double rigid_b) const
    {
      const std::size_t   n = contact_dofs.size();
      std::vector<double> local(2 * n, 0.0), all(2 * n);
      for (std::size_t k = 0; k < n; ++k)
        if (locally_owned.is_element(contact_dofs[k]))
        {
          local[k]     = a(contact_dofs[k]);
          local[n + k] = b(contact_dofs[k]);
        }
      const int ierr = MPI_Allreduce(local.data(),
                                     all.data(),
                                     static_cast<int>(local.size()),
                                     MPI_DOUBLE,
                                     MPI_SUM,
                                     comm);
      AssertThrowMPI(ierr);
      std::vector<double> ca(all.begin(), all.begin() + n), cb(all.begin() + n, all.end());
      ca.push_back(rigid_a);
      cb.push_back(rigid_b);
      return {std::move(ca), std::move(cb)};
    }

    void ImpactProblem::scatter_add(const std::vector<double> &compact, Vec &f) const
    {
      for (unsigned int k = 0; k < contact_dofs.size(); ++k)
        if (compact[k] != 0 && locally_owned.is_element(contact_dofs[k]))
          f(contact_dofs[k]) += compact[k];
      f.compress(VectorOperation::add);
    }

    /** Compact vector of the contact evaluation with the rigid DoF appended if missing. */
    std::vector<double> padded_force(const PenaltyContact::Evaluation &ev, std::size_t size)
    {
      std::vector<double> f = ev.force;
      f.resize(size, 0.0);
      return f;
    }

    void ImpactProblem::record(unsigned long                     n,
                               double                            t,
                               const Vec                        &u,
                               const Vec                        &v_n,
                               const Vec                        &Ku,
                               double                            u_r,
                               double                            v_r,
                               const PenaltyContact::Evaluation &ev,
                               const std::vector<double>        &cu)
    {
      // Contact work by the trapezoid rule over the compact DoFs (the only ones it acts on).
      const std::vector<double> fc = padded_force(ev, cu.size());
      if (!cu_prev.empty())
        for (std::size_t k = 0; k < cu.size(); ++k)
          contact_work += 0.5 * (fc[k] + fc_prev[k]) * (cu[k] - cu_prev[k]);
      cu_prev = cu;
      fc_prev = fc;
      raw_force.push_back(ev.total_force);
      penetration_integral += ev.mean_penetration * dt;
      max_penetration = std::max(max_penetration, ev.max_penetration);

      // Energies and means at the sampled steps only (one reduction): the divergence guard
      // acts within one output interval.
      if (n % sample_every != 0)
        return;
      std::array<double, 4> local{{0, 0, 0, 0}}; // kinetic, strain, slab m u, slab m v
      {
        const double *vp = v_n.begin(), *mp = mass.begin(), *up = u.begin(), *kp = Ku.begin(),
                     *sp = slab_mass_x.begin();
        for (std::size_t k = 0; k < v_n.locally_owned_size(); ++k)
        {
          local[0] += 0.5 * mp[k] * vp[k] * vp[k];
          local[1] += 0.5 * up[k] * kp[k];
          local[2] += sp[k] * up[k];
          local[3] += sp[k] * vp[k];
        }
      }
      std::array<double, 4> global{};
      const int ierr = MPI_Allreduce(local.data(), global.data(), 4, MPI_DOUBLE, MPI_SUM, comm);
      AssertThrowMPI(ierr);
      const double kinetic = global[0] + (prm.rigid_slab ? 0.5 * prm.slab_mass * v_r * v_r : 0);
      const double strain  = global[1];
      const double error   = (kinetic + strain - contact_work) / e0 - 1;
      max_energy_error     = std::max(max_energy_error, std::abs(error));
      if (!std::isfinite(error) || std::abs(error) > divergence_energy_error)
        throw_divergence(n, t, u);

      const double slab_u = prm.rigid_slab ? u_r : global[2] / slab_total_mass;
      const double slab_v = prm.rigid_slab ? v_r : global[3] / slab_total_mass;
      double       wall = 0, front = 0;
      for (std::size_t k = 0; k < cu.size(); ++k)
      {
        wall += wall_weight[k] * cu[k];
        front += front_weight[k] * cu[k];
      }
      history.time.push_back(t);
      history.contact_force.push_back(ev.total_force);
      history.n_active.push_back(ev.active.size());
      history.slab_displacement.push_back(slab_u);
      history.slab_velocity.push_back(slab_v);
      history.wall_displacement.push_back(wall);
      history.indentation.push_back(front - wall - initial_gap);
      history.max_penetration.push_back(ev.max_penetration);
      history.kinetic.push_back(kinetic);
      history.strain.push_back(strain);
      history.penalty.push_back(ev.penalty_energy);
      history.contact_dissipation.push_back(-contact_work - ev.penalty_energy);
      history.energy_error.push_back(error);
      if (prm.log_interval > 0 && (n / sample_every) % prm.log_interval == 0)
        log_line("step " + std::to_string(n) + " t = " + fmt_double(t) + " s, F = " +
                 fmt_double(ev.total_force) + " N/m, active = " + std::to_string(ev.active.size()) +
                 ", max penetration = " + fmt_double(ev.max_penetration) +
                 " m, dE/E0 = " + fmt_double(error));
    }

    void ImpactProblem::throw_divergence(unsigned long n, double t, const Vec &u) const
    {
      // Locate the largest displacement to name the place of the blow-up.
      double     local_max = -1;
      Point<dim> where;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (unsigned int v = 0; v < cell->n_vertices(); ++v)
            for (unsigned int c = 0; c < dim; ++c)
            {
              const auto i = cell->vertex_dof_index(v, c);
              if (!locally_owned.is_element(i))
                continue;
              const double a =
                std::isfinite(u(i)) ? std::abs(u(i)) : std::numeric_limits<double>::max();
              if (a > local_max)
              {
                local_max = a;
                where     = cell->vertex(v);
              }
            }
      const auto all =
        Utilities::MPI::all_gather(comm, std::vector<double>{local_max, where[0], where[1]});
      std::vector<double> worst{-1, 0, 0};
      for (const auto &a : all)
        if (a[0] > worst[0])
          worst = a;
      throw NumericalError("impact diverged at t = " + fmt_double(t) + " s (step " +
                             std::to_string(n) + ", dt = " + fmt_double(dt) +
                             " s): energy not conserved or not finite; largest displacement " +
                             fmt_double(worst[0]) + " m at (" + fmt_double(worst[1]) + ", " +
                             fmt_double(worst[2]) + ") m",
                           t,
                           n);
    }

    void ImpactProblem::output_results(double                     t,
                                       const Vec                 &u,
                                       const Vec                 &v,
                                       const std::vector<double> &contact_force)
    {
      Vec u_g(locally_owned, locally_relevant, comm), v_g(locally_owned, locally_relevant, comm);
      Vec f(locally_owned, comm);
      scatter_add(contact_force, f);
      Vec f_g(locally_owned, locally_relevant, comm);
      u_g = u;
      v_g = v;
      f_g = f;

      Vector<float>        material(triangulation.n_active_cells()), subdomain(material.size());
      Vector<float>        sxx(material.size()), syy(material.size()), sxy(material.size());
      const QMidpoint<dim> midpoint;
      FEValues<dim>        fe_values(fe, midpoint, update_gradients);
      const FEValuesExtractors::Vector     displacement(0);
      std::vector<SymmetricTensor<2, dim>> eps(1);
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
        {
          const unsigned int c = cell->active_cell_index();
          fe_values.reinit(cell);
          fe_values[displacement].get_function_symmetric_gradients(u_g, eps);
          // Stress at the cell centre from the committed history of its first Gauss point.
          const MaterialLaw  &law = *laws.at(cell->material_id());
          std::vector<double> scratch(law.n_history());
          const double       *committed = linear_laws ? scratch.data() : qp_history.committed(c, 0);
          const VoigtStress   sigma =
            law.stress({{eps[0][0][0], eps[0][1][1], 2 * eps[0][0][1]}}, committed, scratch.data());
          material(c)  = cell->material_id();
          subdomain(c) = triangulation.locally_owned_subdomain();
          sxx(c)       = sigma[0];
          syy(c)       = sigma[1];
          sxy(c)       = sigma[2];
        }
      DataOut<dim> data_out;
      data_out.attach_dof_handler(dof_handler);
      const std::vector<DataComponentInterpretation::DataComponentInterpretation> vector_field(
        dim,
        DataComponentInterpretation::component_is_part_of_vector);
      data_out.add_data_vector(u_g,
                               std::vector<std::string>(dim, "displacement"),
                               DataOut<dim>::type_dof_data,
                               vector_field);
      data_out.add_data_vector(v_g,
                               std::vector<std::string>(dim, "velocity"),
                               DataOut<dim>::type_dof_data,
                               vector_field);
      data_out.add_data_vector(f_g,
                               std::vector<std::string>(dim, "contact_force"),
                               DataOut<dim>::type_dof_data,
                               vector_field);
      data_out.add_data_vector(material, "material_id");
      data_out.add_data_vector(subdomain, "subdomain");
      data_out.add_data_vector(sxx, "stress_xx");
      data_out.add_data_vector(syy, "stress_yy");
      data_out.add_data_vector(sxy, "stress_xy");
      data_out.build_patches();
      const unsigned int counter = pvd_records.size();
      const std::string  pvtu =
        data_out.write_vtu_with_pvtu_record(prm.vtu_dir.string() + "/", "impact", counter, comm, 4);
      pvd_records.emplace_back(t, pvtu);
      if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        std::ofstream pvd(prm.vtu_dir / "impact.pvd");
        DataOutBase::write_pvd_record(pvd, pvd_records);
      }
    }

    void ImpactProblem::run_explicit()
    {
      Vec u(locally_owned, comm), v_half(locally_owned, comm), v_n(locally_owned, comm);
      Vec Ku(locally_owned, comm), a(locally_owned, comm);
      // Initial velocity: the slab moves at +initial_velocity in x.
      double u_r = 0, v_r = prm.initial_velocity;
      for (const auto i : locally_owned)
        if (slab_mass_x(i) > 0)
          v_half(i) = prm.initial_velocity;
      v_half.compress(VectorOperation::insert);
      v_n = v_half;

      const bool          write_vtu = !prm.vtu_dir.empty() && prm.vtu_interval > 0;
      const unsigned long vtu_every =
        write_vtu ? std::max<unsigned long>(1, std::lround(prm.vtu_interval / dt)) : 0;
      const unsigned long n_max = static_cast<unsigned long>(std::ceil(prm.end_time / dt));
      const unsigned long hold_steps =
        static_cast<unsigned long>(std::ceil(prm.separation_hold_time / dt));
      bool          started    = false;
      unsigned long zero_since = 0;
      unsigned long n          = 0;
      separated_flag           = false;
      for (;; ++n)
      {
        const double t = n * dt;
        // Contact at (u_n, v_{n-1/2}): the damping lags half a step, which keeps the scheme
        // explicit.
        const auto [cu, cv]          = gather_compact(u, u_r, v_half, v_r);
        const auto                ev = contact->evaluate(cu, cv);
        const std::vector<double> fc = padded_force(ev, cu.size());

        internal_force(u, Ku);
        if (!linear_laws)
          qp_history.commit();
        a.equ(-1.0, Ku);
        scatter_add(fc, a);
        a.scale(inverse_mass);
        const double a_r = prm.rigid_slab ? fc.back() / prm.slab_mass : 0;

        // v_{n+1/2} = v_{n-1/2} + dt a_n (half a step at the start); v_n = mean of the two.
        const double h = n == 0 ? 0.5 * dt : dt;
        v_n            = v_half;
        if (n > 0)
          v_n.add(0.5 * dt, a);
        v_half.add(h, a);
        const double v_r_n = v_r + (n > 0 ? 0.5 * dt * a_r : 0.0);
        v_r += h * a_r;

        record(n, t, u, v_n, Ku, u_r, v_r_n, ev, cu);
        if (prm.progress && n % prm.progress_interval == 0 && n > 0 &&
            Utilities::MPI::this_mpi_process(comm) == 0)
          prm.progress(t, prm.end_time);
        if (write_vtu && n % vtu_every == 0)
          output_results(t, u, v_n, fc);

        if (ev.total_force > 0)
        {
          started    = true;
          zero_since = n + 1;
        }
        if (started && n + 1 - zero_since >= hold_steps && ev.total_force == 0)
        {
          separated_flag = true;
          slab_v_end     = prm.rigid_slab ? v_r_n : (slab_mass_x * v_n) / slab_total_mass;
          break;
        }
        if (n >= n_max)
        {
          slab_v_end = prm.rigid_slab ? v_r_n : (slab_mass_x * v_n) / slab_total_mass;
          break;
        }
        u.add(dt, v_half);
        u_r += dt * v_r;
      }
      n_steps_done = n;
    }

    ImpactProblem::StepOperator &ImpactProblem::step_operator(unsigned int level)
    {
      auto &slot = step_operators[level];
      if (slot)
        return *slot;
      const auto start  = std::chrono::steady_clock::now();
      slot              = std::make_unique<StepOperator>();
      StepOperator &op  = *slot;
      op.dt             = dt / static_cast<double>(1UL << level);
      op.c1             = 1.0 / (newmark_beta * op.dt * op.dt);
      op.rigid_diagonal = prm.rigid_slab ? prm.slab_mass * op.c1 : 0.0;
      op.base.reinit(stiffness);
      op.base.copy_from(stiffness);
      for (const auto i : locally_owned)
        op.base.add(i, i, op.c1 * mass(i));
      op.base.compress(VectorOperation::add);
      if (prm.implicit_solver == ImpactParameters::ImplicitSolver::direct)
      {
        op.direct = std::make_unique<TrilinosWrappers::SolverDirect>(op.control);
        op.direct->initialize(op.base);
        op.flexibility.resize(contact_dofs.size() + 1);
      }
      else
      {
        TrilinosWrappers::PreconditionAMG::AdditionalData data;
        data.elliptic              = true;
        data.higher_order_elements = false;
        data.smoother_sweeps       = 2;
        data.aggregation_threshold = 0.02;
        DoFTools::extract_constant_modes(dof_handler, ComponentMask(), data.constant_modes);
        op.amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
        op.amg->initialize(op.base, data);
        op.system.reinit(op.base);
      }
      const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      linear_setup_seconds += seconds;
      linear_solver_seconds += seconds;
      return op;
    }

    void ImpactProblem::base_solve(StepOperator &op, Vec &x, const Vec &b)
    {
      const auto start = std::chrono::steady_clock::now();
      op.direct->solve(x, b);
      ++n_linear_solves;
      linear_solver_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }

    const std::vector<double> &ImpactProblem::flexibility_column(StepOperator &op, unsigned int k)
    {
      // Column k of the compact block of (K + c1 M)^{-1} (the rigid DoF decouples: 1 / (m c1)).
      auto &column = op.flexibility[k];
      if (!column.empty())
        return column;
      if (k == contact_dofs.size())
      {
        column.assign(contact_dofs.size() + 1, 0.0);
        column.back() = 1.0 / op.rigid_diagonal;
        return column;
      }
      Vec e(locally_owned, comm), x(locally_owned, comm);
      if (locally_owned.is_element(contact_dofs[k]))
        e(contact_dofs[k]) = 1.0;
      e.compress(VectorOperation::insert);
      base_solve(op, x, e);
      column = gather_compact(x, 0.0);
      return column;
    }

    void ImpactProblem::solve_newton_system(StepOperator                     &op,
                                            const PenaltyContact::Evaluation &ev,
                                            const Vec                        &residual,
                                            double                            r_rigid,
                                            Vec                              &du,
                                            double                           &du_r)
    {
      // Newton matrix J = B + sum_i k_i g_i g_i^T, B = K + c1 M (with m c1 on the rigid DoF),
      // g_i = dg/du of active slave i on the free compact DoFs, k_i its tangent penalty.
      const std::size_t r_index = contact_dofs.size();
      std::vector<std::pair<double, std::vector<std::pair<unsigned int, double>>>> g;
      for (const auto &pair : ev.active)
      {
        if (pair.dforce_dpenetration <= 0)
          continue;
        std::vector<std::pair<unsigned int, double>> entries;
        for (unsigned int k = 0; k < pair.n_dofs; ++k)
          if (pair.dofs[k] == r_index || compact_free[pair.dofs[k]])
            entries.emplace_back(pair.dofs[k], pair.dg_du[k]);
        g.emplace_back(pair.dforce_dpenetration, std::move(entries));
      }
      Vec rhs(locally_owned, comm);
      rhs.equ(-1.0, residual);
      if (op.direct)
      {
        // Woodbury: J^{-1} r = x - B^{-1} G S^{-1} G^T x, x = B^{-1} r, S = K^{-1} + G^T B^{-1} G;
        // G^T B^{-1} G needs only the compact block of B^{-1}, cached per step size.
        base_solve(op, du, rhs);
        du_r = prm.rigid_slab ? -r_rigid / op.rigid_diagonal : 0.0;
        if (g.empty())
          return;
        const std::vector<double> xc = gather_compact(du, du_r);
        const unsigned int        m  = g.size();
        FullMatrix<double>        s(m, m);
        Vector<double>            w(m), z(m);
        for (unsigned int i = 0; i < m; ++i)
        {
          for (const auto &[k, gk] : g[i].second)
            w(i) += gk * xc[k];
          s(i, i) += 1.0 / g[i].first;
          for (const auto &[l, gl] : g[i].second)
          {
            const std::vector<double> &column = flexibility_column(op, l);
            for (unsigned int j = 0; j < m; ++j)
              for (const auto &[k, gk] : g[j].second)
                s(j, i) += gk * column[k] * gl;
          }
        }
        s.gauss_jordan();
        s.vmult(z, w);
        std::vector<double> y(r_index + 1, 0.0);
        for (unsigned int i = 0; i < m; ++i)
          for (const auto &[k, gk] : g[i].second)
            y[k] += gk * z(i);
        Vec                 correction(locally_owned, comm), dx(locally_owned, comm);
        std::vector<double> y_nodes(y.begin(), y.end());
        y_nodes.back() = 0;
        scatter_add(y_nodes, correction);
        base_solve(op, dx, correction);
        du -= dx;
        if (prm.rigid_slab)
          du_r -= y.back() / op.rigid_diagonal;
        return;
      }

      // CG + AMG on the assembled J; the rigid DoF by Sherman-Morrison on the Schur complement
      // S = A - b b^T / d (A: free block of J, b: its coupling to the rigid DoF, d: rigid entry).
      double d = op.rigid_diagonal;
      Vec    b(locally_owned, comm), z(locally_owned, comm);
      op.system.copy_from(op.base);
      for (const auto &[k_i, entries] : g)
        for (const auto &[i, gi] : entries)
          for (const auto &[j, gj] : entries)
          {
            const double value = k_i * gi * gj;
            const bool   ri = i == r_index, rj = j == r_index;
            if (ri && rj)
              d += value;
            else if (rj)
            {
              if (locally_owned.is_element(contact_dofs[i]))
                b(contact_dofs[i]) += value;
            }
            else if (!ri && locally_owned.is_element(contact_dofs[i]))
              op.system.add(contact_dofs[i], contact_dofs[j], value);
          }
      op.system.compress(VectorOperation::add);
      b.compress(VectorOperation::add);
      const auto cg_solve = [&](Vec &x, const Vec &f)
      {
        const auto                 start = std::chrono::steady_clock::now();
        SolverControl              control(max_cg_iterations, cg_tolerance * f.l2_norm());
        TrilinosWrappers::SolverCG cg(control);
        x = 0;
        if (f.l2_norm() > 0)
          cg.solve(op.system, x, f, *op.amg);
        ++n_linear_solves;
        linear_solver_seconds +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      };
      du_r = 0;
      if (prm.rigid_slab)
      {
        const double s = -r_rigid;
        rhs.add(-s / d, b);
        cg_solve(du, rhs);
        cg_solve(z, b);
        const double bz1 = b * du, bz2 = b * z;
        du.add(bz1 / (d - bz2), z);
        du_r = (s - (b * du)) / d;
      }
      else
        cg_solve(du, rhs);
    }

    void ImpactProblem::run_implicit()
    {
      Vec u(locally_owned, comm), v(locally_owned, comm), acc(locally_owned, comm);
      Vec u_np1(locally_owned, comm), v_np1(locally_owned, comm), a_np1(locally_owned, comm);
      Vec Ku(locally_owned, comm), residual(locally_owned, comm), du(locally_owned, comm);
      Vec rhs(locally_owned, comm), u_start(locally_owned, comm);
      for (const auto i : locally_owned)
        if (slab_mass_x(i) > 0)
          v(i) = prm.initial_velocity;
      v.compress(VectorOperation::insert);
      double u_r = 0, v_r = prm.initial_velocity, a_r = 0;

      compact_free.assign(contact_dofs.size(), false);
      {
        std::vector<double> local(contact_dofs.size(), 0.0);
        for (unsigned int k = 0; k < contact_dofs.size(); ++k)
          if (locally_owned.is_element(contact_dofs[k]) &&
              !constraints.is_constrained(contact_dofs[k]))
            local[k] = 1;
        std::vector<double> all(local.size());
        const int           ierr = MPI_Allreduce(local.data(),
                                       all.data(),
                                       static_cast<int>(local.size()),
                                       MPI_DOUBLE,
                                       MPI_SUM,
                                       comm);
        AssertThrowMPI(ierr);
        for (unsigned int k = 0; k < contact_dofs.size(); ++k)
          compact_free[k] = all[k] > 0.5;
      }
      // Round-off floor of the residual: |K| |u|.
      const double stiffness_norm = stiffness.linfty_norm();

      const bool          write_vtu = !prm.vtu_dir.empty() && prm.vtu_interval > 0;
      const unsigned long vtu_every =
        write_vtu ? std::max<unsigned long>(1, std::lround(prm.vtu_interval / dt)) : 0;
      const unsigned long n_max = static_cast<unsigned long>(std::ceil(prm.end_time / dt));
      const unsigned long hold_steps =
        static_cast<unsigned long>(std::ceil(prm.separation_hold_time / dt));
      const std::size_t r_index = contact_dofs.size();

      PenaltyContact::Evaluation ev;
      std::vector<double>        cu;
      {
        cu = gather_compact(u, u_r);
        ev = contact->evaluate(cu, gather_compact(v, v_r));
        internal_force(u, Ku);
        record(0, 0.0, u, v, Ku, u_r, v_r, ev, cu);
        if (write_vtu)
          output_results(0.0, u, v, padded_force(ev, cu.size()));
      }

      // One Newmark step of size dt / 2^level from (u, v, acc) into (u_np1, v_np1, a_np1):
      // semi-smooth Newton on the incremental potential
      //   Pi(u) = c1 / 2 |u - u~|_M^2 + u.K u / 2 + sum_i k_i max(0, p_i(u))^2 / 2,
      // whose gradient is the residual R = M a + K u - f_c. Pi is convex and C1 with a piecewise
      // constant Hessian: a full Newton step can jump across the kinks of max(0, p) and cycle
      // between active sets; a line search for the minimum of Pi along the Newton direction
      // cannot. Returns false if Newton fails (the caller halves the step).
      double     t_fail = 0, r_fail = 0, tol_fail = 0;
      double     u_r_np1 = 0, v_r_np1 = 0, a_r_np1 = 0;
      const auto newton_step = [&](unsigned int level) -> bool
      {
        StepOperator &op  = step_operator(level);
        const double  h   = op.dt;
        const double  c1  = op.c1;
        const double  c2  = 1.0 / (2 * newmark_beta) - 1;
        const double  m_r = prm.rigid_slab ? prm.slab_mass : 0.0;
        u_np1             = u;
        u_np1.add(h, v, 0.5 * h * h, acc);
        u_r_np1              = u_r + h * v_r + 0.5 * h * h * a_r;
        double       r_rigid = 0, scale = 0, r_norm = 0;
        const double momentum_rate = slab_total_mass * prm.initial_velocity / h;
        const auto   evaluate      = [&]()
        {
          a_np1 = u_np1;
          a_np1.add(-1.0, u, -h, v);
          a_np1.sadd(c1, -c2, acc);
          v_np1 = v;
          v_np1.add(h * (1 - newmark_gamma), acc, h * newmark_gamma, a_np1);
          a_r_np1 = c1 * (u_r_np1 - u_r - h * v_r) - c2 * a_r;
          v_r_np1 = v_r + h * ((1 - newmark_gamma) * a_r + newmark_gamma * a_r_np1);

          const auto gathered          = gather_compact(u_np1, u_r_np1, v_np1, v_r_np1);
          cu                           = gathered.first;
          ev                           = contact->evaluate(cu, gathered.second);
          const std::vector<double> fc = padded_force(ev, cu.size());
          internal_force(u_np1, Ku);
          residual = a_np1;
          residual.scale(mass);
          const double inertia_norm = residual.l2_norm();
          residual += Ku;
          rhs = 0;
          scatter_add(fc, rhs);
          residual -= rhs;
          residual.scale(free_mask);
          r_rigid = prm.rigid_slab ? m_r * a_r_np1 - fc[r_index] : 0.0;
          scale = inertia_norm + Ku.l2_norm() + ev.total_force + stiffness_norm * u_np1.l2_norm() +
                  momentum_rate + m_r * std::abs(a_r_np1) + std::numeric_limits<double>::min();
          r_norm = std::sqrt(residual.norm_sqr() + r_rigid * r_rigid);
        };
        evaluate();
        for (unsigned int k = 0;; ++k)
        {
          if (r_norm <= newton_tolerance * scale)
            return true;
          if (k == prm.implicit_newton_max_iterations)
          {
            r_fail   = r_norm;
            tol_fail = newton_tolerance * scale;
            return false;
          }
          ++n_newton;
          double du_r = 0;
          solve_newton_system(op, ev, residual, r_rigid, du, du_r);
          du.scale(free_mask);
          const double slope = residual * du + r_rigid * du_r;
          if (!(slope < 0))
          {
            // Not a descent direction: only round-off is left in the residual.
            if (r_norm <= newton_roundoff_tolerance * scale)
              return true;
            r_fail   = r_norm;
            tol_fail = newton_tolerance * scale;
            return false;
          }
          // Line search on phi(alpha) = Pi(u + alpha du), convex, through its derivative
          // phi'(alpha) = R(u + alpha du) . du, which (unlike Pi itself, a sum of large terms)
          // stays accurate down to the Newton tolerance: the full step if phi'(1) <= 0 (Pi falls
          // all the way), else regula falsi (Illinois) for the minimum until |phi'| has fallen
          // by line_search_reduction. A history law has no Pi; the same search on R . du is
          // then a heuristic.
          u_start                = u_np1;
          const double u_r_start = u_r_np1;
          const auto   phi_prime = [&](double step)
          {
            u_np1 = u_start;
            u_np1.add(step, du);
            u_r_np1 = u_r_start + step * du_r;
            evaluate();
            return residual * du + r_rigid * du_r;
          };
          double alpha = 1, lo = 0, hi = 1, phi_lo = slope, phi_hi = phi_prime(1.0);
          bool   accepted = phi_hi <= 0 || r_norm <= newton_tolerance * scale;
          for (unsigned int ls = 0; !accepted && ls < max_line_search; ++ls)
          {
            alpha                    = (lo * phi_hi - hi * phi_lo) / (phi_hi - phi_lo);
            const double phi         = phi_prime(alpha);
            accepted                 = std::abs(phi) <= line_search_reduction * std::abs(slope);
            const bool left          = phi < 0;
            (left ? lo : hi)         = alpha;
            (left ? phi_lo : phi_hi) = phi;
            // Illinois: halve the value kept at the end that did not move.
            (left ? phi_hi : phi_lo) *= 0.5;
          }
          if (!accepted)
          {
            r_fail   = r_norm;
            tol_fail = newton_tolerance * scale;
            return false;
          }
        }
      };

      bool          started    = false;
      unsigned long zero_since = 0;
      unsigned long n          = 0;
      // Time in ticks of the smallest allowed step, dt / 2^max_halvings.
      const unsigned int  max_level      = prm.implicit_max_halvings;
      const unsigned long ticks_per_step = 1UL << max_level;
      unsigned long       ticks          = 0;
      unsigned int        level          = 0;
      while (n < n_max)
      {
        const unsigned long step_ticks = ticks_per_step >> level;
        const double        t_np1 =
          static_cast<double>(ticks + step_ticks) * dt / static_cast<double>(ticks_per_step);
        if (!newton_step(level))
        {
          if (!linear_laws)
            qp_history.revert();
          t_fail = t_np1;
          if (level == max_level)
            throw NumericalError("Newton on the contact did not converge at t = " +
                                   fmt_double(t_fail) + " s (step " + std::to_string(n + 1) +
                                   ", dt halved " + std::to_string(level) + " times to " +
                                   fmt_double(step_operator(level).dt) + " s, the floor; " +
                                   std::to_string(ev.active.size()) +
                                   " active contact nodes): residual " + fmt_double(r_fail) +
                                   " N/m vs tolerance " + fmt_double(tol_fail),
                                 t_fail,
                                 n + 1);
          ++level;
          ++n_step_halvings;
          continue;
        }
        if (!linear_laws)
          qp_history.commit();
        u.swap(u_np1);
        v.swap(v_np1);
        acc.swap(a_np1);
        u_r = u_r_np1;
        v_r = v_r_np1;
        a_r = a_r_np1;
        ticks += step_ticks;
        // Grow back once the substeps are aligned with the coarser grid.
        while (level > 0 && ticks % (ticks_per_step >> (level - 1)) == 0)
          --level;
        if (ticks % ticks_per_step != 0)
          continue;
        ++n;
        record(n, t_np1, u, v, Ku, u_r, v_r, ev, cu);
        if (write_vtu && n % vtu_every == 0)
          output_results(t_np1, u, v, padded_force(ev, cu.size()));
        if (prm.progress && n % prm.progress_interval == 0 &&
            Utilities::MPI::this_mpi_process(comm) == 0)
          prm.progress(t_np1, prm.end_time);

        if (ev.total_force > 0)
        {
          started    = true;
          zero_since = n + 1;
        }
        if (started && n + 1 - zero_since >= hold_steps && ev.total_force == 0)
        {
          separated_flag = true;
          break;
        }
      }
      slab_v_end   = prm.rigid_slab ? v_r : (slab_mass_x * v) / slab_total_mass;
      n_steps_done = n;
    }

    void ImpactProblem::finish(ImpactResult &result, double wall_seconds)
    {
      // Impulse-preserving smoothing: a centred moving average (zero padded) over the window;
      // sum(F) dt is unchanged because the force is zero at both ends of the run.
      const double period =
        prm.smoothing_window > 0 ? prm.smoothing_window : contact_width / contact_wave_speed;
      const long          half  = std::max(0L, static_cast<long>(std::floor(0.5 * period / dt)));
      const long          n_raw = static_cast<long>(raw_force.size());
      std::vector<double> prefix(n_raw + 1, 0.0);
      for (long i = 0; i < n_raw; ++i)
        prefix[i + 1] = prefix[i] + raw_force[i];
      const auto smoothed = [&](long i)
      {
        const long lo = std::max(0L, i - half), hi = std::min(n_raw - 1, i + half);
        return (prefix[hi + 1] - prefix[lo]) / static_cast<double>(2 * half + 1);
      };

      ImpactSummary &s     = result.summary;
      long           first = -1, last = -1;
      for (long i = 0; i < n_raw; ++i)
      {
        s.peak_force_raw = std::max(s.peak_force_raw, raw_force[i]);
        s.peak_force     = std::max(s.peak_force, smoothed(i));
        s.impulse += raw_force[i] * dt;
        if (raw_force[i] > 0)
        {
          if (first < 0)
            first = i;
          last = i;
        }
      }
      for (std::size_t j = 0; j < history.time.size(); ++j)
        history.smoothed_contact_force.push_back(smoothed(static_cast<long>(j * sample_every)));
      if (first >= 0)
      {
        s.contact_start    = first * dt;
        s.contact_duration = (last - first + 1) * dt;
      }
      s.rebound_velocity = slab_v_end;
      s.apparent_cor     = -slab_v_end / prm.initial_velocity;
      s.energy_error     = max_energy_error;
      s.smoothing_window = (2 * half + 1) * dt;
      s.max_penetration  = max_penetration;
      s.mean_penetration = s.contact_duration > 0 ? penetration_integral / s.contact_duration : 0;
      s.initial_gap      = initial_gap;
      for (const auto &sl : contact->slaves())
        s.penalty_stiffness = std::max(s.penalty_stiffness, sl.stiffness);
      s.n_dofs                = dof_handler.n_dofs();
      s.n_cells               = triangulation.n_global_active_cells();
      s.n_steps               = n_steps_done;
      s.n_newton              = n_newton;
      s.n_step_halvings       = n_step_halvings;
      s.n_linear_solves       = n_linear_solves;
      s.linear_solver_seconds = linear_solver_seconds;
      s.linear_setup_seconds  = linear_setup_seconds;
      s.dt                    = dt;
      s.dt_stable             = dt_stable;
      s.wall_seconds          = wall_seconds;
      s.n_ranks               = Utilities::MPI::n_mpi_processes(comm);
      s.separated             = separated_flag;
      result.history          = std::move(history);
    }

    ImpactResult ImpactProblem::run()
    {
      const auto start = std::chrono::steady_clock::now();
      validate_parameters();
      make_grid();
      setup_system();
      make_laws();
      // The lumped mass is needed by the contact setup (reduced masses), the contact DoFs by the
      // implicit sparsity pattern: assemble the mass first with a provisional pattern.
      contact_dofs.clear();
      assemble_system();
      setup_contact();
      if (prm.integrator == ImpactParameters::Integrator::implicit_newmark)
        assemble_system();
      compute_time_step();
      e0 = 0.5 * slab_total_mass * prm.initial_velocity * prm.initial_velocity;
      log_line("mesh: " + std::to_string(triangulation.n_global_active_cells()) + " cells, " +
               std::to_string(dof_handler.n_dofs()) + " DoFs on " +
               std::to_string(Utilities::MPI::n_mpi_processes(comm)) +
               " ranks; dt = " + fmt_double(dt) + " s (stable " + fmt_double(dt_stable) +
               " s, mesh omega " + fmt_double(omega_mesh) + " rad/s, penalty omega " +
               fmt_double(omega_penalty) + " rad/s)");
      if (prm.integrator == ImpactParameters::Integrator::explicit_central_difference)
        run_explicit();
      else
        run_implicit();
      if (prm.progress && Utilities::MPI::this_mpi_process(comm) == 0)
        prm.progress(n_steps_done * dt, prm.end_time);
      ImpactResult result;
      finish(result,
             std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      log_line("done: " + std::to_string(result.summary.n_steps) + " steps, peak force " +
               fmt_double(result.summary.peak_force) + " N/m, contact " +
               fmt_double(result.summary.contact_duration) + " s, impulse " +
               fmt_double(result.summary.impulse) + " N s/m, COR " +
               fmt_double(result.summary.apparent_cor) + ", max |dE/E0| " +
               fmt_double(result.summary.energy_error) + ", " +
               fmt_double(result.summary.wall_seconds) + " s");
      return result;
    }
  } // namespace
} // namespace kimp::fem

namespace kimp::fem
{
  ImpactResult run_impact(const ImpactParameters &parameters, MPI_Comm comm, std::ostream *log)
  {
    ImpactProblem problem(parameters, comm, log);
    return problem.run();
  }
} // namespace kimp::fem
