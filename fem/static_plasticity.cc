// Static plane-strain plasticity (see static_plasticity.h; its meshes and initial stress in
// plane_mesh.cc), one cohesive algorithm: B-bar operators precomputed per Gauss point, residual and
// consistent-tangent assembly, full Newton with a direct solve, load steps halved when Newton
// fails.
#include "fem/static_plasticity.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include "fem/frictional_interface.h"
#include "fem/mean_dilatation.h"

namespace kimp::fem
{
  namespace
  {
    using namespace dealii;
    constexpr int          dim = 2;
    constexpr unsigned int n_q = 4, n_d = 8; // Q1: 2 x 2 Gauss points, 8 DoFs per cell

    /** Solves the 3 x 3 system d x = b (row-major). */
    VoigtStrain solve3(const VoigtTangent &d, const VoigtStress &b)
    {
      const VoigtStrain x = solve_tangent(d, b);
      if (!std::isfinite(x[0] + x[1] + x[2]))
        throw std::invalid_argument("initial stress: the law's virgin tangent is singular");
      return x;
    }

    /** Central difference of the law's stress at @p e from the committed history @p h. */
    VoigtTangent difference_tangent(const MaterialLaw   &law,
                                    const VoigtStrain   &e,
                                    const double        *h,
                                    std::vector<double> &scratch)
    {
      const double d = 1e-7 * std::max({std::abs(e[0]), std::abs(e[1]), std::abs(e[2]), 1e-6});
      return central_difference_tangent([&](const VoigtStrain &x)
                                        { return law.stress(x, h, scratch.data()); },
                                        e,
                                        d);
    }

    /** Refuses a parameter the static solve cannot honour. */
    [[noreturn]] void bad(const std::string &what)
    {
      throw std::invalid_argument(what);
    }

    class StaticProblem
    {
    public:
      explicit StaticProblem(const StaticPlasticityParameters &p);
      StaticPlasticityResult run(std::ostream *log);

    private:
      /** r = f_int(u) - f_ext at every DoF; writes the trial history. */
      void residual(const Vector<double> &u, Vector<double> &r);
      /** Tangent at u (committed history) into matrix_; rhs = -r - K lift at the free DoFs. */
      void   assemble(const Vector<double> &u,
                      const Vector<double> &r,
                      const Vector<double> &lift,
                      Vector<double>       &rhs);
      double relative_residual(const Vector<double> &r) const;
      /** |r| over the prescribed DoFs (N/m). */
      double fixed_norm(const Vector<double> &r) const;
      /** |r| over the free DoFs (N/m). */
      double                             free_norm(const Vector<double> &r) const;
      std::vector<std::array<double, 2>> reactions(const Vector<double> &r) const;
      /** Newton from u (residual r) with the prescribed increment lift; false if it fails.
       *  With @p loose, a stalled iteration ends at its best iterate if that one is within
       *  loose_tolerance. */
      bool newton(Vector<double>       &u,
                  Vector<double>       &r,
                  const Vector<double> &lift,
                  std::vector<double>  &residuals,
                  bool                  loose = false);
      /** One attempt at the step from load factor a to b, halved @p depth times: true if it
       *  converged (committed and appended to out.steps); false, the state restored, if it is
       *  to be halved. One that cannot be halved any more throws NumericalError. */
      bool attempt(double a, double b, unsigned int depth, StaticPlasticityResult &out);
      /** The extrapolated predictor (StaticPlasticityParameters::extrapolated_predictor): from
       *  the lifted state @p u, the free DoFs and the controlled load moved on by the last
       *  converged step's increments times predictor_ratio_; kept (u, r and the baseline)
       *  if its out-of-balance force is lower. */
      void extrapolate(Vector<double> &u, Vector<double> &r, double &baseline, double &norm);
      /** The segments of p.load_path in load steps of at most 1 / n_steps, halved and grown
       *  back by the step control (StaticPlasticityParameters::grow_after). */
      void walk_load_path(StaticPlasticityResult &out);
      /** One segment from load factor @p start to @p end in @p n full steps. */
      void walk_segment(double start, double end, unsigned int n, StaticPlasticityResult &out);
      VoigtStrain strain(const Vector<double> &u, unsigned int c, unsigned int q) const;
      /** The triangulation of p.mesh and its DoFs. */
      void build_mesh();
      /** The prescribed DoFs (the later entry governs a shared one), their constraints and the
       *  sparsity of matrix_. */
      void prescribe_displacements();
      /** Per Gauss point: B-bar (Voigt), JxW, eigenstrain of the initial stress; body force. */
      void precompute_points();
      /** The interface of p.interface on the vertices' DoFs (none if empty). */
      void setup_interface();
      /** The interface's displacements (compact node numbering) at u. */
      std::vector<double> interface_displacements(const Vector<double> &u) const;
      /** Adds the interface's tangent (central differences of its forces per pair) to matrix_
       *  and its lift term to rhs. */
      void
      assemble_interface(const Vector<double> &u, const Vector<double> &lift, Vector<double> &rhs);
      /** MaterialLaw::begin_step() on every committed point for a step of @p increment of
       *  the load factor. */
      void begin_step(double increment);
      void commit();
      void revert();
      /** The final state of @p cell (StaticPlasticityResult::CellState); adds its dissipation to
       *  @p out's totals. */
      StaticPlasticityResult::CellState cell_state(const FEValues<dim>    &fv,
                                                   StaticPlasticityResult &out) const;
      /** The largest MaterialLaw::step_error() of the trial history (the converged iterate). */
      double largest_step_error() const;
      /** The unit-resultant band traction vector g_ of p.controlled_load. */
      void setup_controlled_load();
      /** Adds the bordered part of a Newton update: du += dP b with K b = g, dP such that the
       *  band's mean displacement at u + lift + du is its target; returns dP. */
      double border(SparseDirectUMFPACK &solver, const Vector<double> &u, Vector<double> &du) const;
      /** |g.u - target| within round-off of the controlled displacement. */
      bool controlled_mean_reached(const Vector<double> &u) const;

      const StaticPlasticityParameters    &p_;
      Triangulation<dim>                   tria_;
      FESystem<dim>                        fe_;
      DoFHandler<dim>                      dof_handler_;
      std::vector<const MaterialLaw *>     cell_law_;
      std::vector<bool>                    cell_fd_;   // numerical tangent per cell
      std::vector<types::global_dof_index> cell_dofs_; // n_cells x n_d
      std::vector<double>                  bbar_;      // n_cells x n_q x n_d x 3
      std::vector<double>                  jxw_;       // n_cells x n_q
      std::vector<VoigtStrain>             eps0_;      // n_cells x n_q
      // n_cells x n_q: the stress of the last residual(), whose trial history a commit keeps.
      std::vector<VoigtStress>             stress_;
      std::vector<VoigtTangent>            virgin_;      // per cell: its law's virgin tangent
      std::vector<int>                     governed_by_; // per DoF: entry or -1
      std::vector<unsigned int>            component_;   // per DoF
      Vector<double>                       f_ext_, target_, u_, r_;
      AffineConstraints<double>            constraints_;
      SparsityPattern                      pattern_;
      SparseMatrix<double>                 matrix_;
      QuadraturePointHistory               history_;
      std::unique_ptr<FrictionalInterface> interface_;
      std::vector<types::global_dof_index> interface_dofs_; // 2 per compact node
      std::size_t                          segment_ = 0;
      bool segment_ended_ = false; // p.end_segment ended the segment at the last converged step
      Vector<double> g_;           // controlled load, unit resultant
      double         load_           = 0; // its resultant P, N/m
      double         target_mean_    = 0; // m
      double         weight_         = 0;
      double         last_increment_ = 0;  // load factor increment of the last converged step
      Vector<double> last_du_;             // displacement increment of the last converged step
      double         last_dload_      = 0; // its change of the controlled load, N/m
      double         predictor_ratio_ = 0; // this step's increment over the last one (0: none)
      double         force_scale_     = 0; // largest converged |reactions|
      unsigned long  step_            = 0;
      std::ostream  *log_             = nullptr;
      double         floor_           = 0; // the tangent floor of the current Newton solve
      unsigned long  n_iterations_    = 0; // Newton iterations of the run
      unsigned int   depth_           = 0; // halvings of the current step size
      unsigned int   n_easy_          = 0; // consecutive easy steps at that size
    };

    StaticProblem::StaticProblem(const StaticPlasticityParameters &p)
      : p_(p)
      , fe_(FE_Q<dim>(1), dim)
    {
      if (p.mesh.cells.empty())
        bad("static plasticity: the mesh has no cells");
      if (!(p.tangent_floor >= 0 && p.tangent_floor < 1))
        bad("static plasticity: tangent_floor = " + std::to_string(p.tangent_floor) +
            " (must be in [0, 1))");
      if (p.n_steps == 0 || !(p.newton_tolerance > 0) || p.max_iterations == 0)
        bad("static plasticity: n_steps, newton_tolerance and max_iterations must be > 0");
      if (p.max_cuts > 30)
        bad("static plasticity: max_cuts = " + std::to_string(p.max_cuts) + " (must be <= 30)");
      if (!(p.gravity >= 0))
        bad("static plasticity: gravity = " + std::to_string(p.gravity) + " (must be >= 0)");
      for (const auto &[id, rho] : p.densities)
        if (!(rho >= 0))
          bad("static plasticity: density of material " + std::to_string(id) + " = " +
              std::to_string(rho) + " (must be >= 0)");
      build_mesh();
      setup_interface();
      prescribe_displacements();
      precompute_points();
      setup_controlled_load();
      const unsigned int n_dofs = dof_handler_.n_dofs();
      u_.reinit(n_dofs);
      r_.reinit(n_dofs);
    }

    void StaticProblem::build_mesh()
    {
      const StaticPlasticityParameters &p = p_;
      std::vector<Point<dim>>           vertices;
      for (const auto &v : p.mesh.vertices)
        vertices.emplace_back(v[0], v[1]);
      std::vector<CellData<dim>> cells(p.mesh.cells.size());
      for (std::size_t c = 0; c < cells.size(); ++c)
      {
        const auto &mc = p.mesh.cells[c];
        for (unsigned int k = 0; k < 4; ++k)
          if (mc.vertices[k] >= vertices.size())
            bad("static plasticity: cell " + std::to_string(c) + " names vertex " +
                std::to_string(mc.vertices[k]) + " of " + std::to_string(vertices.size()));
        cells[c].vertices    = {mc.vertices[0], mc.vertices[1], mc.vertices[2], mc.vertices[3]};
        cells[c].material_id = mc.material;
        const auto it        = p.laws.find(mc.material);
        if (it == p.laws.end() || !it->second)
          bad("static plasticity: no material law for material id " + std::to_string(mc.material));
      }
      SubCellData boundary;
      for (const auto &e : p.mesh.boundary_edges)
      {
        CellData<1> line;
        line.vertices    = {e.vertices[0], e.vertices[1]};
        line.boundary_id = static_cast<types::boundary_id>(e.boundary);
        boundary.boundary_lines.push_back(line);
      }
      tria_.create_triangulation(vertices, cells, boundary);
      dof_handler_.reinit(tria_);
      dof_handler_.distribute_dofs(fe_);
    }

    void StaticProblem::prescribe_displacements()
    {
      const unsigned int n_dofs = dof_handler_.n_dofs();
      governed_by_.assign(n_dofs, -1);
      component_.assign(n_dofs, 0);
      target_.reinit(n_dofs);
      std::vector<types::global_dof_index> face_dofs(fe_.n_dofs_per_face());
      for (std::size_t e = 0; e < p_.prescribed.size(); ++e)
      {
        const auto &pd    = p_.prescribed[e];
        bool        found = false;
        for (const auto &cell : dof_handler_.active_cell_iterators())
          for (const auto f : cell->face_indices())
            if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == pd.boundary_id)
            {
              found = true;
              cell->face(f)->get_dof_indices(face_dofs);
              for (unsigned int i = 0; i < face_dofs.size(); ++i)
              {
                const unsigned int comp = fe_.face_system_to_component_index(i).first;
                if ((comp == 0 && pd.x) || (comp == 1 && pd.y))
                {
                  governed_by_[face_dofs[i]] = static_cast<int>(e);
                  target_[face_dofs[i]]      = comp == 0 ? pd.ux : pd.uy;
                }
              }
            }
        if (!found)
          bad("static plasticity: prescribed displacement on boundary id " +
              std::to_string(pd.boundary_id) + ", which has no edge in the mesh");
      }
      for (unsigned int d = 0; d < n_dofs; ++d)
        if (governed_by_[d] >= 0)
          constraints_.add_line(d);
      constraints_.close();
      DynamicSparsityPattern dsp(n_dofs);
      DoFTools::make_sparsity_pattern(dof_handler_, dsp, constraints_, false);
      for (std::size_t k = 0; k < p_.interface.size(); ++k)
        for (unsigned int i = 0; i < 4; ++i)
          for (unsigned int j = 0; j < 4; ++j)
            dsp.add(interface_dofs_[4 * k + i], interface_dofs_[4 * k + j]);
      pattern_.copy_from(dsp);
      matrix_.reinit(pattern_);
    }

    void StaticProblem::precompute_points()
    {
      const unsigned int n_dofs = dof_handler_.n_dofs(), n_cells = tria_.n_active_cells();
      const StaticPlasticityParameters &p         = p_;
      unsigned int                      n_history = 0;
      for (const auto &[id, law] : p.laws)
        n_history = std::max(n_history, law->n_history());
      history_.reinit(n_cells, n_q, n_history);
      cell_law_.resize(n_cells);
      cell_fd_.resize(n_cells);
      cell_dofs_.resize(n_cells * n_d);
      bbar_.resize(n_cells * n_q * n_d * 3);
      jxw_.resize(n_cells * n_q);
      eps0_.assign(n_cells * n_q, VoigtStrain{});
      stress_.assign(n_cells * n_q, VoigtStress{});
      f_ext_.reinit(n_dofs);
      const QGauss<dim>                    quadrature(2);
      FEValues<dim>                        fv(fe_,
                       quadrature,
                       update_values | update_gradients | update_JxW_values |
                         update_quadrature_points);
      std::vector<types::global_dof_index> dofs(n_d);
      for (const auto &cell : dof_handler_.active_cell_iterators())
      {
        const unsigned int c = cell->active_cell_index();
        fv.reinit(cell);
        cell->get_dof_indices(dofs);
        std::copy(dofs.begin(), dofs.end(), cell_dofs_.begin() + c * n_d);
        const MaterialLaw &law = *p.laws.at(cell->material_id());
        cell_law_[c]           = &law;
        cell_fd_[c]            = p.numerical_tangent.count(cell->material_id()) > 0;
        double anchored_height = 0;
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              p.anchoring_boundaries.count(cell->face(f)->boundary_id()) > 0)
            anchored_height = cell->extent_in_direction(1);
        history_.initialize_cell(c, law, std::sqrt(cell->measure()), anchored_height);
        virgin_.push_back(law.tangent(VoigtStrain{}, history_.committed(c, 0)));
        const auto   rho_it = p.densities.find(cell->material_id());
        const double gamma  = (rho_it == p.densities.end() ? 0.0 : rho_it->second) * p.gravity;
        for (unsigned int q = 0; q < n_q; ++q)
        {
          const double w    = fv.JxW(q);
          jxw_[c * n_q + q] = w;
          weight_ += gamma * w;
          double *B = &bbar_[(c * n_q + q) * n_d * 3];
          for (unsigned int i = 0; i < n_d; ++i)
          {
            const unsigned int comp = fe_.system_to_component_index(i).first;
            component_[dofs[i]]     = comp;
            const auto g            = fv.shape_grad_component(i, q, comp);
            B[3 * i + 0]            = comp == 0 ? g[0] : 0.0;
            B[3 * i + 1]            = comp == 1 ? g[1] : 0.0;
            B[3 * i + 2]            = comp == 0 ? g[1] : g[0];
            if (comp == 1)
              f_ext_[dofs[i]] -= gamma * fv.shape_value_component(i, q, comp) * w;
          }
          if (p.initial_stress)
          {
            const Point<dim> x = fv.quadrature_point(q);
            eps0_[c * n_q + q] = solve3(law.tangent(VoigtStrain{}, history_.committed(c, q)),
                                        p.initial_stress(x[0], x[1]));
          }
        }
        if (p.bbar)
          for (unsigned int i = 0; i < n_d; ++i)
          {
            // The B-bar column of DoF i: its strain at the points with the mean dilatation.
            std::array<VoigtStrain, n_q> column;
            for (unsigned int q = 0; q < n_q; ++q)
              std::copy_n(&bbar_[((c * n_q + q) * n_d + i) * 3], 3, column[q].begin());
            average_in_plane_trace(column.data(), &jxw_[c * n_q], n_q);
            for (unsigned int q = 0; q < n_q; ++q)
              std::copy_n(column[q].begin(), 3, &bbar_[((c * n_q + q) * n_d + i) * 3]);
          }
      }
    }

    VoigtStrain StaticProblem::strain(const Vector<double> &u, unsigned int c, unsigned int q) const
    {
      VoigtStrain                    e    = eps0_[c * n_q + q];
      const double                  *B    = &bbar_[(c * n_q + q) * n_d * 3];
      const types::global_dof_index *dofs = &cell_dofs_[c * n_d];
      for (unsigned int i = 0; i < n_d; ++i)
      {
        const double ui = u[dofs[i]];
        e[0] += B[3 * i] * ui;
        e[1] += B[3 * i + 1] * ui;
        e[2] += B[3 * i + 2] * ui;
      }
      return e;
    }

    void StaticProblem::residual(const Vector<double> &u, Vector<double> &r)
    {
      r = f_ext_;
      r *= -1.0;
      for (unsigned int c = 0; c < cell_law_.size(); ++c)
      {
        const types::global_dof_index *dofs = &cell_dofs_[c * n_d];
        for (unsigned int q = 0; q < n_q; ++q)
        {
          const VoigtStress s =
            cell_law_[c]->stress(strain(u, c, q), history_.committed(c, q), history_.trial(c, q));
          stress_[c * n_q + q] = s;
          const double *B      = &bbar_[(c * n_q + q) * n_d * 3];
          const double  w      = jxw_[c * n_q + q];
          for (unsigned int i = 0; i < n_d; ++i)
            r[dofs[i]] += (B[3 * i] * s[0] + B[3 * i + 1] * s[1] + B[3 * i + 2] * s[2]) * w;
        }
      }
      if (p_.controlled_load)
        r.add(-load_, g_);
      if (interface_)
      {
        // The pairs' forces act on the nodes like external forces.
        const FrictionalInterface::Evaluation e = interface_->evaluate(interface_displacements(u));
        for (std::size_t d = 0; d < interface_dofs_.size(); ++d)
          r[interface_dofs_[d]] -= e.force[d];
      }
    }

    void StaticProblem::setup_interface()
    {
      if (p_.interface.empty())
        return;
      std::vector<std::array<types::global_dof_index, 2>> vertex_dofs(
        tria_.n_vertices(),
        {{numbers::invalid_dof_index, numbers::invalid_dof_index}});
      for (const auto &cell : dof_handler_.active_cell_iterators())
        for (const auto v : cell->vertex_indices())
          for (unsigned int comp = 0; comp < dim; ++comp)
            vertex_dofs[cell->vertex_index(v)][comp] = cell->vertex_dof_index(v, comp);
      std::vector<FrictionalInterface::Pair> pairs;
      for (std::size_t k = 0; k < p_.interface.size(); ++k)
      {
        const StaticInterfacePair &sp = p_.interface[k];
        for (const unsigned int v : {sp.vertex_a, sp.vertex_b})
          if (v >= vertex_dofs.size() || vertex_dofs[v][0] == numbers::invalid_dof_index)
            bad("static plasticity: interface pair " + std::to_string(k) + " names vertex " +
                std::to_string(v) + ", which no cell uses");
        for (const unsigned int v : {sp.vertex_a, sp.vertex_b})
          for (unsigned int comp = 0; comp < dim; ++comp)
            interface_dofs_.push_back(vertex_dofs[v][comp]);
        FrictionalInterface::Pair pair;
        pair.a                    = static_cast<unsigned int>(2 * k);
        pair.b                    = static_cast<unsigned int>(2 * k + 1);
        pair.nx                   = sp.nx;
        pair.ny                   = sp.ny;
        pair.normal_stiffness     = sp.normal_stiffness;
        pair.tangential_stiffness = sp.tangential_stiffness;
        pair.friction             = sp.friction;
        pairs.push_back(pair);
      }
      interface_ =
        std::make_unique<FrictionalInterface>(std::move(pairs),
                                              static_cast<unsigned int>(2 * p_.interface.size()));
    }

    std::vector<double> StaticProblem::interface_displacements(const Vector<double> &u) const
    {
      std::vector<double> out(interface_dofs_.size());
      for (std::size_t d = 0; d < out.size(); ++d)
        out[d] = u[interface_dofs_[d]];
      return out;
    }

    void StaticProblem::assemble_interface(const Vector<double> &u,
                                           const Vector<double> &lift,
                                           Vector<double>       &rhs)
    {
      // Each pair's consistent tangent (FrictionalInterface::tangent: open, stick or slip from the
      // committed history; a pair exactly at the no-tension kink, as every pair at the start of
      // step 0 where the backfill is placed against the wall, takes the closed side's stick
      // springs, docs/physics.md §6 "Static pushover", "Newton"), plus floor_ times the springs:
      // an open or sliding pair keeps a floor of them in the Newton matrix. Over the pair's DoFs
      // (a_x, a_y, b_x, b_y) the block is [[A, -A], [-A, A]].
      const std::vector<double>            uc = interface_displacements(u);
      FullMatrix<double>                   k(4, 4);
      Vector<double>                       k_lift(4);
      std::vector<types::global_dof_index> dofs(4);
      for (std::size_t pair = 0; pair < p_.interface.size(); ++pair)
      {
        std::array<double, 4> a = interface_->tangent(pair, uc, false);
        if (floor_ > 0)
        {
          const std::array<double, 4> springs = interface_->tangent(pair, uc, true);
          for (unsigned int e = 0; e < 4; ++e)
            a[e] += floor_ * springs[e];
        }
        for (unsigned int i = 0; i < 4; ++i)
          for (unsigned int j = 0; j < 4; ++j)
            k(i, j) = ((i < 2) == (j < 2) ? 1.0 : -1.0) * a[2 * (i % 2) + j % 2];
        for (unsigned int i = 0; i < 4; ++i)
        {
          dofs[i]   = interface_dofs_[4 * pair + i];
          k_lift[i] = 0;
          for (unsigned int j = 0; j < 4; ++j)
            k_lift[i] -= k(i, j) * lift[interface_dofs_[4 * pair + j]];
        }
        constraints_.distribute_local_to_global(k, k_lift, dofs, matrix_, rhs);
      }
    }

    void StaticProblem::setup_controlled_load()
    {
      if (!p_.controlled_load)
        return;
      g_.reinit(dof_handler_.n_dofs());
      const QGauss<dim - 1>                quadrature(2);
      FEFaceValues<dim>                    fv(fe_, quadrature, update_values | update_JxW_values);
      std::vector<types::global_dof_index> dofs(n_d);
      double                               length = 0;
      for (const auto &cell : dof_handler_.active_cell_iterators())
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              cell->face(f)->boundary_id() == p_.controlled_load->boundary_id)
          {
            fv.reinit(cell, f);
            cell->get_dof_indices(dofs);
            for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              length += fv.JxW(q);
              for (unsigned int i = 0; i < n_d; ++i)
                if (fe_.system_to_component_index(i).first == 0)
                  g_[dofs[i]] += fv.shape_value_component(i, q, 0) * fv.JxW(q);
            }
          }
      if (!(length > 0))
        bad("static plasticity: controlled load on boundary id " +
            std::to_string(p_.controlled_load->boundary_id) + ", which has no edge in the mesh");
      g_ /= length;
      for (unsigned int d = 0; d < g_.size(); ++d)
        if (governed_by_[d] >= 0 && g_[d] != 0)
          bad("static plasticity: the controlled load's edges have prescribed displacements");
    }

    double StaticProblem::border(SparseDirectUMFPACK  &solver,
                                 const Vector<double> &u,
                                 Vector<double>       &du) const
    {
      Vector<double> b(u.size());
      solver.vmult(b, g_);
      const double gb = g_ * b;
      // gb < 0 is a softening structure (a falling band force), which the control follows.
      if (!(std::abs(gb) > 0) || !std::isfinite(gb))
        throw NumericalError("static plasticity: the controlled load meets no stiffness", 0, 0);
      const double dp = (target_mean_ - g_ * u - g_ * du) / gb;
      du.add(dp, b);
      return dp;
    }

    bool StaticProblem::controlled_mean_reached(const Vector<double> &u) const
    {
      if (!p_.controlled_load)
        return true;
      return std::abs(g_ * u - target_mean_) <=
             1e-9 * std::max(std::abs(p_.controlled_load->displacement), 1e-12);
    }

    void StaticProblem::begin_step(double increment)
    {
      // Ratio of this increment to the last converged one; none to extrapolate from at the
      // first step or at a reversal of the load path.
      const double ratio = last_increment_ != 0 ? std::max(0.0, increment / last_increment_) : 0.0;
      for (unsigned int c = 0; c < cell_law_.size(); ++c)
        for (unsigned int q = 0; q < n_q; ++q)
          cell_law_[c]->begin_step(history_.committed(c, q), ratio);
      history_.revert(); // the trial history starts from the extrapolated one
    }

    void StaticProblem::commit()
    {
      history_.commit();
      if (interface_)
        interface_->commit();
    }

    double StaticProblem::largest_step_error() const
    {
      double error = 0;
      for (unsigned int c = 0; c < cell_law_.size(); ++c)
        for (unsigned int q = 0; q < n_q; ++q)
          error = std::max(error, cell_law_[c]->step_error(history_.trial(c, q)));
      return error;
    }

    void StaticProblem::revert()
    {
      history_.revert();
      if (interface_)
        interface_->revert();
    }

    void StaticProblem::assemble(const Vector<double> &u,
                                 const Vector<double> &r,
                                 const Vector<double> &lift,
                                 Vector<double>       &rhs)
    {
      matrix_ = 0;
      rhs.reinit(u.size());
      std::vector<double>                  scratch(history_.n_values());
      FullMatrix<double>                   k(n_d, n_d);
      Vector<double>                       k_lift(n_d);
      std::vector<types::global_dof_index> dofs(n_d);
      for (unsigned int c = 0; c < cell_law_.size(); ++c)
      {
        k = 0;
        std::copy(&cell_dofs_[c * n_d], &cell_dofs_[c * n_d] + n_d, dofs.begin());
        for (unsigned int q = 0; q < n_q; ++q)
        {
          const VoigtStrain e = strain(u, c, q);
          VoigtTangent      t =
            cell_fd_[c] ? difference_tangent(*cell_law_[c], e, history_.committed(c, q), scratch) :
                               cell_law_[c]->tangent(e, history_.committed(c, q));
          if (floor_ > 0)
            for (unsigned int a = 0; a < 9; ++a)
              t[a] += floor_ * virgin_[c][a];
          const double *B = &bbar_[(c * n_q + q) * n_d * 3];
          const double  w = jxw_[c * n_q + q];
          for (unsigned int j = 0; j < n_d; ++j)
          {
            // t B_j, then B_i . (t B_j)
            const double *bj = B + 3 * j;
            double        tb[3];
            for (unsigned int a = 0; a < 3; ++a)
              tb[a] = t[3 * a] * bj[0] + t[3 * a + 1] * bj[1] + t[3 * a + 2] * bj[2];
            for (unsigned int i = 0; i < n_d; ++i)
              k(i, j) += (B[3 * i] * tb[0] + B[3 * i + 1] * tb[1] + B[3 * i + 2] * tb[2]) * w;
          }
        }
        for (unsigned int i = 0; i < n_d; ++i)
        {
          k_lift[i] = 0;
          for (unsigned int j = 0; j < n_d; ++j)
            k_lift[i] -= k(i, j) * lift[dofs[j]];
        }
        constraints_.distribute_local_to_global(k, k_lift, dofs, matrix_, rhs);
      }
      if (interface_)
        assemble_interface(u, lift, rhs);
      for (unsigned int d = 0; d < rhs.size(); ++d)
        rhs[d] = governed_by_[d] >= 0 ? 0.0 : rhs[d] - r[d];
    }

    double StaticProblem::relative_residual(const Vector<double> &r) const
    {
      double free = 0, fixed = 0;
      for (unsigned int d = 0; d < r.size(); ++d)
        (governed_by_[d] >= 0 ? fixed : free) += r[d] * r[d];
      // The largest reaction of the run so far keeps the reference when a softening body unloads
      // (its reactions fall to zero while round-off stays at the scale of the peak force).
      const double reference =
        std::max({f_ext_.l2_norm(), std::sqrt(fixed), force_scale_, std::abs(load_)});
      if (free == 0)
        return 0;
      return reference > 0 ? std::sqrt(free) / reference : std::numeric_limits<double>::infinity();
    }

    double StaticProblem::fixed_norm(const Vector<double> &r) const
    {
      double fixed = 0;
      for (unsigned int d = 0; d < r.size(); ++d)
        if (governed_by_[d] >= 0)
          fixed += r[d] * r[d];
      return std::sqrt(fixed);
    }

    double StaticProblem::free_norm(const Vector<double> &r) const
    {
      double free = 0;
      for (unsigned int d = 0; d < r.size(); ++d)
        if (governed_by_[d] < 0)
          free += r[d] * r[d];
      return std::sqrt(free);
    }

    std::vector<std::array<double, 2>> StaticProblem::reactions(const Vector<double> &r) const
    {
      std::vector<std::array<double, 2>> out(p_.prescribed.size(), {{0.0, 0.0}});
      for (unsigned int d = 0; d < r.size(); ++d)
        if (governed_by_[d] >= 0)
          out[governed_by_[d]][component_[d]] += r[d];
      return out;
    }

    void
    StaticProblem::extrapolate(Vector<double> &u, Vector<double> &r, double &baseline, double &norm)
    {
      if (!p_.extrapolated_predictor || !(predictor_ratio_ > 0) || last_du_.size() != u.size())
        return;
      Vector<double> trial = u;
      for (unsigned int d = 0; d < u.size(); ++d)
        if (governed_by_[d] < 0)
          trial[d] += predictor_ratio_ * last_du_[d];
      const double load0 = load_;
      load_ += predictor_ratio_ * last_dload_;
      Vector<double> r_trial(u.size());
      residual(trial, r_trial);
      const double trial_norm = free_norm(r_trial);
      if (controlled_mean_reached(trial) && std::isfinite(trial_norm) && trial_norm < norm)
      {
        u        = trial;
        r        = r_trial;
        baseline = relative_residual(r);
        norm     = trial_norm;
        return;
      }
      load_ = load0;
      residual(u, r); // the trial history of the lifted state
    }

    bool StaticProblem::newton(Vector<double>       &u,
                               Vector<double>       &r,
                               const Vector<double> &lift,
                               std::vector<double>  &residuals,
                               bool                  loose)
    {
      Vector<double>       rhs, du(u.size());
      const Vector<double> zero(u.size());
      Vector<double>       best_u;
      double               best_rel = std::numeric_limits<double>::infinity(), best_load = 0;
      double               damping = 0; // Levenberg-Marquardt factor on the diagonal
      // The acceptance of an update compares the free out-of-balance force itself (N/m): the
      // relative residual's reference moves with the iterate's reactions (a lifted state's are
      // large), so comparing relative values could reject an update that lowers the force.
      double baseline = std::numeric_limits<double>::infinity(), baseline_norm = baseline;
      double last_norm = baseline;
      bool   lifted    = false;
      try
      {
        if (p_.damped_newton)
        {
          // The prescribed increment applied first: the damped iteration then only accepts
          // updates that improve on that state.
          u += lift;
          residual(u, r);
          // A band whose mean is not yet at its target is no state to keep.
          if (controlled_mean_reached(u))
          {
            baseline      = relative_residual(r);
            baseline_norm = free_norm(r);
          }
          lifted = true;
          extrapolate(u, r, baseline, baseline_norm);
        }
        for (unsigned int k = 0; k < p_.max_iterations; ++k)
        {
          const Vector<double> &l = k == 0 && !lifted ? lift : zero;
          // The floor: fixed, or the iterate's relative out-of-balance force below it.
          const double current = k == 0 ? baseline : residuals.back();
          floor_               = p_.floor_follows_residual && std::isfinite(current) ?
                                   std::min(p_.tangent_floor, current) :
                                   p_.tangent_floor;
          ++n_iterations_;
          assemble(u, r, l, rhs);
          if (damping > 0)
            for (unsigned int d = 0; d < u.size(); ++d)
              if (governed_by_[d] < 0)
                matrix_.set(d, d, matrix_.diag_element(d) * (1 + damping));
          SparseDirectUMFPACK solver;
          solver.initialize(matrix_);
          solver.vmult(du, rhs);
          const double load0 = load_;
          double       dp    = 0;
          if (p_.controlled_load)
          {
            Vector<double> shifted = u;
            shifted += l;
            dp = border(solver, shifted, du);
          }
          // Backtracking on the residual norm: full steps near the solution (quadratic rate),
          // shorter ones while the active sets of the return mappings still switch.
          const Vector<double> u0            = u;
          const double         previous      = k == 0 ? baseline : residuals.back();
          const double         previous_norm = k == 0 ? baseline_norm : last_norm;
          double               rel = 0, norm = 0;
          for (unsigned int cut = 0;; ++cut)
          {
            const double alpha = std::pow(0.5, cut);
            u                  = u0;
            u.add(alpha, du);
            u += l;
            load_ = load0 + alpha * dp;
            residual(u, r);
            rel = relative_residual(r);
            // Plain Newton keeps its line search on the relative residual.
            norm = p_.damped_newton ? free_norm(r) : rel;
            if ((std::isfinite(norm) && norm < previous_norm) || cut == p_.max_line_search)
              break;
          }
          if (p_.damped_newton && !(norm < previous_norm))
          {
            // Levenberg-Marquardt: reject the update, damp the next one harder.
            u     = u0;
            load_ = load0;
            residual(u, r);
            rel     = previous;
            norm    = previous_norm;
            damping = damping == 0 ? 1e-2 : 4 * damping;
          }
          else if (p_.damped_newton)
            damping = damping < 1e-4 ? 0.0 : damping / 4;
          last_norm = norm;
          residuals.push_back(rel);
          if (!std::isfinite(rel))
            return false;
          if (rel <= p_.newton_tolerance && controlled_mean_reached(u))
            return true;
          if (loose && rel < best_rel && controlled_mean_reached(u))
          {
            best_rel  = rel;
            best_u    = u;
            best_load = load_;
          }
        }
        if (loose && best_rel <= p_.loose_tolerance)
        {
          u     = best_u;
          load_ = best_load;
          residual(u, r); // the trial history of that iterate
          residuals.push_back(best_rel);
          return true;
        }
      }
      catch (const std::exception &)
      {
        // A singular tangent or a failed return mapping: the step is cut like a stalled one.
        return false;
      }
      return false;
    }

    bool StaticProblem::attempt(double a, double b, unsigned int depth, StaticPlasticityResult &out)
    {
      step_                       = out.steps.size();
      const Vector<double> u_save = u_, r_save = r_;
      const double         load_save = load_;
      target_mean_ = p_.controlled_load ? b * p_.controlled_load->displacement : 0.0;
      Vector<double> lift(u_.size());
      for (unsigned int d = 0; d < lift.size(); ++d)
        if (governed_by_[d] >= 0)
          lift[d] = target_[d] * (b - a);
      StaticStep step;
      step.load_factor = b;
      step.segment     = segment_;
      const bool loose = p_.loose_tolerance > 0 && depth >= p_.max_cuts;
      begin_step(b - a);
      predictor_ratio_ = last_increment_ != 0 ? (b - a) / last_increment_ : 0.0;
      bool converged   = newton(u_, r_, lift, step.residuals, loose);
      if (converged && p_.step_error_tolerance > 0)
      {
        const double error = largest_step_error();
        if (error > p_.step_error_tolerance && depth < std::min(p_.max_error_cuts, p_.max_cuts))
        {
          converged = false; // halved below
          ++out.step_control.n_error_cuts;
        }
        else if (error > p_.step_error_tolerance)
        {
          ++out.step_control.n_large_error_steps;
          out.step_control.largest_step_error =
            std::max(out.step_control.largest_step_error, error);
        }
      }
      if (converged)
      {
        last_increment_ = b - a;
        last_du_        = u_;
        last_du_ -= u_save;
        last_dload_ = load_ - load_save;
        if (step.residuals.back() > p_.newton_tolerance)
        {
          ++out.step_control.n_loose_steps;
          out.step_control.largest_loose_residual =
            std::max(out.step_control.largest_loose_residual, step.residuals.back());
        }
        commit();
        step.reactions        = reactions(r_);
        step.controlled_force = load_;
        force_scale_          = std::max({force_scale_, fixed_norm(r_), std::abs(load_)});
        if (log_ != nullptr)
        {
          std::ostringstream line; // 4 significant digits
          line.precision(4);
          line << "static step " << out.steps.size() << ": load factor " << b << ", "
               << step.residuals.size() << " Newton iterations, residual " << step.residuals.back();
          if (p_.controlled_load)
            line << ", controlled load " << step.controlled_force << " N/m";
          for (std::size_t e = 0; e < step.reactions.size(); ++e)
            line << ", reaction " << e << " (" << step.reactions[e][0] << ", "
                 << step.reactions[e][1] << ") N/m";
          *log_ << line.str() << '\n';
        }
        out.steps.push_back(std::move(step));
        segment_ended_ = p_.end_segment && p_.end_segment(out.steps, segment_);
        return true;
      }
      revert();
      load_ = load_save;
      u_    = u_save;
      r_    = r_save;
      if (depth >= p_.max_cuts)
      {
        std::ostringstream msg; // 4 significant digits: the message reaches reports
        msg.precision(4);
        msg << "static plasticity: load step " << step_ << " (load factor " << a << " -> " << b
            << ") did not converge in " << p_.max_iterations << " Newton iterations after " << depth
            << " halvings; relative residuals:";
        for (const double x : step.residuals)
          msg << ' ' << x;
        throw NumericalError(msg.str(), b, step_);
      }
      if (log_ != nullptr && !step.residuals.empty())
      {
        std::ostringstream line;
        line.precision(4);
        line << "static step " << out.steps.size() << ": load factor " << a << " -> " << b
             << " halved after " << step.residuals.size() << " Newton iterations; residuals "
             << step.residuals.front() << " ... "
             << *std::min_element(step.residuals.begin(), step.residuals.end()) << " (least) ... "
             << step.residuals.back();
        *log_ << line.str() << '\n';
      }
      return false;
    }

    void StaticProblem::walk_segment(double                  start,
                                     double                  end,
                                     unsigned int            n,
                                     StaticPlasticityResult &out)
    {
      // Positions in units of the smallest step: a step of depth d spans fine >> d of them and
      // starts on a multiple of that, so halving and doubling keep the walk on the grid.
      const unsigned long fine = 1ul << p_.max_cuts, total = n * fine;
      unsigned long       pos = 0;
      while (pos < total)
      {
        const unsigned long next = pos + (fine >> depth_);
        const double        a    = start + (end - start) * static_cast<double>(pos) / total;
        const double        b    = start + (end - start) * static_cast<double>(next) / total;
        segment_ended_           = false;
        const std::size_t n_cuts = out.step_control.n_error_cuts;
        if (!attempt(a, b, depth_, out))
        {
          if (out.step_control.n_error_cuts == n_cuts)
            ++out.step_control.n_newton_cuts;
          ++depth_;
          n_easy_ = 0;
          continue;
        }
        pos                        = next;
        const std::size_t n_newton = out.steps.back().residuals.size();
        const bool        easy     = n_newton <= std::max(1u, p_.max_iterations / 4) &&
                          out.steps.back().residuals.back() <= p_.newton_tolerance;
        n_easy_ = easy ? n_easy_ + 1 : 0;
        if (segment_ended_) // an unloading that reached zero force
          return;
        // Growing back: bisection (grow_after 0) returns to the largest step whose grid the
        // walk is on; the step control doubles once after grow_after easy steps.
        while (depth_ > 0 && pos % (fine >> (depth_ - 1)) == 0 &&
               (p_.grow_after == 0 || n_easy_ >= p_.grow_after))
        {
          --depth_;
          if (p_.grow_after > 0)
          {
            n_easy_ = 0;
            break;
          }
        }
      }
    }

    void StaticProblem::walk_load_path(StaticPlasticityResult &out)
    {
      const std::vector<double> path =
        p_.load_path.empty() ? std::vector<double>{1.0} : p_.load_path;
      double factor = 0;
      for (segment_ = 0; segment_ < path.size(); ++segment_)
      {
        const double       start = factor, end = path[segment_];
        const unsigned int n =
          std::max(1u,
                   static_cast<unsigned int>(std::ceil(p_.n_steps * std::abs(end - start) - 1e-9)));
        if (p_.grow_after == 0) // bisection: every segment starts with a full step
          depth_ = 0;
        walk_segment(start, end, n, out);
        factor = out.steps.back().load_factor;
      }
    }

    StaticPlasticityResult::CellState StaticProblem::cell_state(const FEValues<dim>    &fv,
                                                                StaticPlasticityResult &out) const
    {
      const auto                       &cell = fv.get_cell();
      const unsigned int                c    = cell->active_cell_index();
      const Point<dim>                  x    = cell->center();
      StaticPlasticityResult::CellState state;
      state.centre = {{x[0], x[1]}};
      state.size   = {{cell->extent_in_direction(0), cell->extent_in_direction(1)}};
      double area = 0, cracked = 0;
      for (unsigned int q = 0; q < n_q; ++q)
      {
        const VoigtStrain  e = strain(u_, c, q);
        const double      *h = history_.committed(c, q);
        const PointOutput  o = cell_law_[c]->output(e, h);
        const VoigtStress &s = stress_[c * n_q + q];
        const double       w = jxw_[c * n_q + q];
        out.plastic_dissipation += o.plastic_dissipation * w;
        out.damage_dissipation += o.damage_dissipation * w;
        state.damage += o.damage / n_q;
        state.plastic_strain = std::max(state.plastic_strain, o.equivalent_plastic_strain);
        const double dx      = fv.quadrature_point(q)[0] - x[0];
        for (unsigned int i = 0; i < 3; ++i)
          state.stress[i] += s[i] * w;
        state.reinforcement_stress[0] += o.reinforcement_stress_xx * w;
        state.reinforcement_stress[1] += o.reinforcement_stress_yy * w;
        state.stress_moment[0] += dx * s[0] * w;
        state.stress_moment[1] += dx * s[1] * w;
        state.stress_moment[2] += dx * o.reinforcement_stress_yy * w;
        state.stress_moment[3] += (fv.quadrature_point(q)[1] - x[1]) * s[2] * w;
        state.tension_damage += o.tension_damage * w;
        if (o.tension_damage > 0)
        {
          state.crack_normal_yy += o.crack_normal_yy * w;
          cracked += w;
        }
        area += w;
      }
      for (double &v : state.stress)
        v /= area;
      for (double &v : state.reinforcement_stress)
        v /= area;
      for (double &v : state.stress_moment)
        v /= area;
      state.tension_damage /= area;
      state.crack_normal_yy = cracked > 0 ? state.crack_normal_yy / cracked : 0.0;
      return state;
    }

    StaticPlasticityResult StaticProblem::run(std::ostream *log)
    {
      log_ = log;
      StaticPlasticityResult out;
      out.n_dofs = dof_handler_.n_dofs();
      out.weight = weight_;
      // Step 0: gravity and initial stress with the prescribed parts held.
      residual(u_, r_);
      {
        double free = 0;
        for (unsigned int d = 0; d < r_.size(); ++d)
          if (governed_by_[d] < 0)
            free += r_[d] * r_[d];
        out.initial_out_of_balance = weight_ > 0 ? std::sqrt(free) / weight_ : std::sqrt(free);
      }
      StaticStep step0;
      if (relative_residual(r_) > p_.newton_tolerance)
      {
        const Vector<double> zero(u_.size());
        if (!newton(u_, r_, zero, step0.residuals))
          throw NumericalError("static plasticity: the initial state (gravity and initial "
                               "stress) did not reach equilibrium in " +
                                 std::to_string(p_.max_iterations) + " Newton iterations",
                               0.0,
                               0);
      }
      commit();
      if (log_ != nullptr && !step0.residuals.empty())
      {
        std::ostringstream line; // 4 significant digits
        line.precision(4);
        line << "static step 0 (gravity and initial stress): " << step0.residuals.size()
             << " Newton iterations, residual " << step0.residuals.back();
        *log_ << line.str() << '\n';
      }
      step0.reactions        = reactions(r_);
      step0.controlled_force = load_;
      out.steps.push_back(step0);
      walk_load_path(out);

      // Totals, cell states and vertex displacements.
      out.cell_states.resize(cell_law_.size());
      FEValues<dim> fv(fe_, QGauss<dim>(2), update_quadrature_points);
      for (const auto &cell : dof_handler_.active_cell_iterators())
      {
        fv.reinit(cell);
        out.cell_states[cell->active_cell_index()] = cell_state(fv, out);
      }
      out.step_control.n_newton_iterations = n_iterations_;
      out.vertex_displacements.assign(tria_.n_vertices(), {{0.0, 0.0}});
      for (const auto &cell : dof_handler_.active_cell_iterators())
        for (const auto v : cell->vertex_indices())
          for (unsigned int comp = 0; comp < dim; ++comp)
            out.vertex_displacements[cell->vertex_index(v)][comp] =
              u_[cell->vertex_dof_index(v, comp)];
      return out;
    }
  } // namespace

  StaticPlasticityResult run_static_plasticity(const StaticPlasticityParameters &parameters,
                                               std::ostream                     *log)
  {
    StaticProblem problem(parameters);
    return problem.run(log);
  }
} // namespace kimp::fem
