#include "accel/primitive_query.h"

#include "accel/ray_query.h"

namespace prism {

bool update_closest(const SceneGeometry& geometry, PrimitiveQuery& query, PrimitiveId id,
                    std::optional<Hit>& best) {
  const std::optional<PrimitiveHit> h = intersect_primitive(geometry, query, id);
  if (!h) return false;
  if (best && !comes_before(h->t, id.geom_id, id.prim_id, *best)) return false;
  best = Hit{h->t, h->u, h->v, id.geom_id, id.prim_id};
  query.narrow(h->t);
  return true;
}

}  // namespace prism
