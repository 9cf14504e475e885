// ImpactProblem state after the impact: the wall's permanent indentation (the static displacement
// left after elastic unloading from the end state) and its displacement at the end of the run.
#include <algorithm>
#include <cmath>

#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>

#include "fem/impact/impact_problem.h"
#include "geometry/scene_ids.h"

namespace kimp::fem::internal
{
  using namespace dealii;

  namespace
  {
    /** Relative residual of the unloading solve. */
    constexpr double unloading_tolerance = 1e-10;

    /**
     * K on the DoFs of mask 1 (wall and soil), the identity on the others (the elastic slab,
     * which K leaves free): m K (m x) + (1 - m) x, symmetric positive definite.
     */
    class MaskedStiffness
    {
    public:
      MaskedStiffness(const TrilinosWrappers::SparseMatrix &k, const Vec &mask)
        : k_(k)
        , mask_(mask)
        , tmp_(mask)
      {
      }
      void vmult(Vec &dst, const Vec &src) const
      {
        tmp_ = src;
        tmp_.scale(mask_);
        k_.vmult(dst, tmp_);
        dst.scale(mask_);
        dst += src;
        dst -= tmp_;
      }

    private:
      const TrilinosWrappers::SparseMatrix &k_;
      const Vec                            &mask_;
      mutable Vec                           tmp_;
    };

    /** Jacobi preconditioner: the inverse diagonal. */
    class InverseDiagonal
    {
    public:
      explicit InverseDiagonal(const Vec &inverse)
        : inverse_(inverse)
      {
      }
      void vmult(Vec &dst, const Vec &src) const
      {
        dst = src;
        dst.scale(inverse_);
      }

    private:
      const Vec &inverse_;
    };
  } // namespace

  void ImpactProblem::compute_residual_state(const Vec &u, double u_r)
  {
    const std::vector<double> cu = gather_compact(u, u_r);
    wall_end_displacement        = 0;
    for (std::size_t k = 0; k < cu.size(); ++k)
      wall_end_displacement += wall_weight[k] * cu[k];
    permanent_wall_indentation = 0;
    if (linear_laws)
      return; // no history: the unloaded body is undeformed

    // Force of the history alone at the start state, f_int(u_0; h) (u_0 = 0, or the geostatic
    // state, which the initial history balances): zero for damage (secant unloading), the
    // eigenstress of the plastic strains otherwise.
    Vec zero(locally_owned, comm), f0(locally_owned, comm);
    internal_force(geostatic_on ? geostatic_u : zero, f0);
    qp_history.revert(); // an evaluation after the run: leave the end state committed
    Vec rhs(locally_owned, comm);
    rhs.equ(-1.0, f0);
    if (rhs.l2_norm() == 0)
      return;

    // Wall and soil only: the elastic slab's DoFs (free in K) are held by the identity.
    Vec mask(locally_owned, comm), inverse_diagonal(locally_owned, comm);
    mask = 1.0;
    std::vector<types::global_dof_index> dof_indices(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial() && cell->material_id() == geometry::slab_material)
      {
        cell->get_dof_indices(dof_indices);
        for (const auto i : dof_indices)
          if (locally_owned.is_element(i))
            mask(i) = 0.0;
      }
    mask.compress(VectorOperation::insert);
    for (const auto i : locally_owned)
    {
      const double d      = mask(i) > 0 ? stiffness.diag_element(i) : 1.0;
      inverse_diagonal(i) = d > 0 ? 1.0 / d : 1.0;
    }
    inverse_diagonal.compress(VectorOperation::insert);
    rhs.scale(mask);

    const MaskedStiffness operator_k(stiffness, mask);
    SolverControl         control(20 * dof_handler.n_dofs(), unloading_tolerance * rhs.l2_norm());
    SolverCG<Vec>         cg(control);
    Vec                   x(locally_owned, comm);
    cg.solve(operator_k, x, rhs, InverseDiagonal(inverse_diagonal));
    const std::vector<double> cx = gather_compact(x, 0.0);
    for (std::size_t k = 0; k < cx.size(); ++k)
      permanent_wall_indentation += wall_weight[k] * cx[k];
    unloading_iterations = control.last_step();
  }
} // namespace kimp::fem::internal
