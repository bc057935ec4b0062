#pragma once

// Draggable points of a project: everything the editor's select/move tool can grab, as one list.

#include <sylva/folding/Edit.hpp>
#include <sylva/folding/Project.hpp>

#include <optional>
#include <vector>

namespace sylva::folding {

/** One draggable point of a zone, in the zone image's pixel coordinates (Project.hpp). */
struct Handle {
  /** What the handle moves. */
  enum class Kind : std::uint8_t {
    ZoneVertex,  ///< a corner of the zone's shape (rect corners 0..3 as Shape::outline())
    PointFrom,   ///< points tool: where the content comes from (a)
    PointTo,     ///< points tool: where it goes (b)
    CurveSource, ///< curve tool: control point `index` of the source curve
    CurveDest,   ///< curve tool: control point `index` of the destination curve
    LassoFrom,   ///< lasso tool: polygon vertex before the deform
    LassoTo,     ///< lasso tool: the same vertex after it
    ZeroPoint,   ///< zero tool: polyline vertex
    ScaleCentre, ///< scale tool: its centre
    FoldVertex,  ///< folding polygon `tool` (the polygon index), vertex `index`
  };
  /** What the handle moves. */
  Kind kind = Kind::ZoneVertex;
  /** The zone it belongs to. */
  int zone = 0;
  int tool = -1; ///< tool index (FoldVertex: folding polygon index; ZoneVertex: −1)
  int index = 0; ///< vertex, pair or control point
  /** Where it is, zone image pixels. */
  Vec2 pos{0.0};

  /** Every field equal. */
  bool operator==(const Handle&) const = default;
};

/** Every handle of zone `zone`, in a stable order (shape, then tools in order, then folding polygons). */
std::vector<Handle> zoneHandles(const Project& project, int zone);
/** Every handle of every zone on image `image` (id). */
std::vector<Handle> imageHandles(const Project& project, const std::string& image);
/** Moves `handle` to `position` in `project` (throws std::out_of_range when it no longer exists). */
void setHandle(Project& project, const Handle& handle, Vec2 position);
/** The edit: moves a handle; `coalesce` for the motion events of one drag (EditHistory::apply). */
void moveHandle(EditHistory& history, const Handle& handle, Vec2 position, bool coalesce = false);
/**
 * The handle nearest to `p` within `maxDistance` (same units as p), preferring later handles on ties (what
 * is drawn on top); nullopt when none is that close.
 */
std::optional<Handle> nearestHandle(const std::vector<Handle>& handles, Vec2 p, double maxDistance);

} // namespace sylva::folding
