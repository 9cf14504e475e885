// Validation and mesh ladder of the docs/physics.md §4 scene parameters.
#include "geometry/scene_geometry.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace kimp::geometry
{
  namespace
  {
    std::string metres(double value)
    {
      std::ostringstream out;
      out.precision(10);
      out << value << " m";
      return out.str();
    }

    [[noreturn]] void
    reject(const std::string &name, double value, const std::string &unit, const std::string &rule)
    {
      std::ostringstream message;
      message.precision(10);
      message << "geometry." << name << " = " << value;
      if (!unit.empty())
        message << ' ' << unit;
      message << " (" << rule << ')';
      throw std::invalid_argument(message.str());
    }

    // Written as !(value > 0) so that NaN is rejected too.
    void require_positive(const std::string &name, double value)
    {
      if (!(value > 0.0) || !std::isfinite(value))
        reject(name, value, "m", "must be > 0 and finite");
    }
  } // namespace


  double SceneGeometry::resolved_backfill_height() const
  {
    return backfill_height.value_or(wall_height);
  }


  double SceneGeometry::resolved_slab_top() const
  {
    return slab_top.value_or(wall_height);
  }


  double SceneGeometry::slab_bottom() const
  {
    return resolved_slab_top() - slab_thickness;
  }


  void SceneGeometry::validate() const
  {
    require_positive("wall_height", wall_height);
    require_positive("wall_thickness", wall_thickness);
    require_positive("slab_length", slab_length);
    require_positive("slab_thickness", slab_thickness);

    if (!(gap > 0.0) || !std::isfinite(gap))
      reject("gap", gap, "m", "must be > 0: a slab touching or overlapping the wall is refused");

    if (with_backfill)
    {
      require_positive("backfill_width", backfill_width);
      const double h_b = resolved_backfill_height();
      require_positive("backfill_height", h_b);
      if (h_b > wall_height)
        reject("backfill_height", h_b, "m", "must be <= wall_height = " + metres(wall_height));
    }

    const double top = resolved_slab_top();
    if (!std::isfinite(top))
      reject("slab_top", top, "m", "must be finite");
    if (top > wall_height)
      reject("slab_top",
             top,
             "m",
             "must be <= wall_height = " + metres(wall_height) +
               ": the slab must face the wall, not pass above its top");
    if (top - slab_thickness < 0.0)
      reject("slab_top",
             top,
             "m",
             "must be >= slab_thickness = " + metres(slab_thickness) +
               ": the slab bottom would be below the ground y = 0");

    require_positive("h_contact", h_contact);
    require_positive("h_max", h_max);
    if (h_contact > h_max)
      reject("h_contact", h_contact, "m", "must be <= h_max = " + metres(h_max));
    if (h_contact > wall_thickness)
      reject("h_contact",
             h_contact,
             "m",
             "must be <= wall_thickness = " + metres(wall_thickness) +
               ": at least one element through the wall");
    if (h_contact > slab_thickness)
      reject("h_contact",
             h_contact,
             "m",
             "must be <= slab_thickness = " + metres(slab_thickness) +
               ": at least one element over the slab front");
    if (!(grading >= 1.0) || !std::isfinite(grading))
      reject("grading",
             grading,
             "",
             "must be >= 1 and finite: size ratio of neighbouring elements");
    if (wall_aspect_max && (!(*wall_aspect_max >= 1.0) || !std::isfinite(*wall_aspect_max)))
      reject("wall_aspect_max",
             *wall_aspect_max,
             "",
             "must be >= 1 and finite: largest height/width of the wall's cells");
  }


  SceneGeometry refined(const SceneGeometry &geometry, int level)
  {
    if (level < 0 || level > 10)
      throw std::invalid_argument("geometry refinement level = " + std::to_string(level) +
                                  " (must be in [0, 10])");
    SceneGeometry result = geometry;
    const double  factor = std::ldexp(1.0, -level);
    result.h_contact *= factor;
    result.h_max *= factor;
    return result;
  }
} // namespace kimp::geometry
