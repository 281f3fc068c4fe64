"""A live run of a large mesh on a proxy: the mesh's inputs carried to the proxy, its result back.

Above the object's Proxy Threshold a live run solves on a gauss_core.Proxy (a simplified copy whose
vertices are the mesh's own) and writes ``proxy.transfer`` into the whole mesh at every tick; Enter
finishes the whole mesh at full resolution (session.py, live_run.py). What the artist set on the whole
mesh acts on the proxy:

- pins: a proxy vertex is pinned where the mesh vertex it is is pinned; a pinned mesh vertex the
  proxy collapsed away pins the corner of the proxy face it rides on nearest to it, so a small Pin
  Group never vanishes from the proxy;
- Regions and painted strength: a proxy face takes the mean weight of the mesh vertices that ride on
  it (fine_map), not only of its three corners, so a painted stroke narrower than a proxy face still
  counts; a face no mesh vertex rides on takes its corners' mean.

Numpy only, no Blender data: it runs on the set-up's worker thread as well as on the main one.
"""

import numpy as np

# The proxy's size, the top of the 50,000-100,000 the issue asks for: small enough that its steps run
# live on two cores (in Blender at 2M vertices 9-11 a second against 12-14 at 75,000), large enough to
# keep a sculpt's silhouette and creases and to finish close to a run from scratch (at 2M vertices
# 0.30% of the diagonal away, against 0.41% at 75,000: docs/performance.md, "The proxy's size").
PROXY_VERTICES = 100000


def proxy_size(num_vertices, threshold):
    """How many vertices a live run's proxy of a mesh of ``num_vertices`` gets, or None when the mesh
    is not above ``threshold`` (the object's Proxy Threshold) and runs at full resolution. Never more
    than the threshold: a proxy is never bigger than a mesh that runs without one."""
    if num_vertices <= threshold:
        return None
    return max(4, min(PROXY_VERTICES, threshold, num_vertices))


class ProxyMap:
    """gauss_core.Proxy of a mesh and what the run's inputs become on it.

    proxy:     the gauss_core.Proxy
    fine:      (#P,) int64, the mesh vertex each proxy vertex is
    riding:    (#V,) int64, the proxy vertex nearest each mesh vertex within the face it rides on
               (itself for a proxy vertex; -1 where it rides on no face)
    """

    def __init__(self, gauss_core, coords, triangles, target):
        self.proxy = gauss_core.Proxy(coords, triangles, int(target))
        self.fine = np.asarray(self.proxy.fine_of_proxy, np.int64)
        self.vertices = np.asarray(self.proxy.vertices, np.float64)
        self.triangles = np.asarray(self.proxy.triangles, np.int32)
        self.num_vertices = len(self.fine)
        self.num_fine = int(self.proxy.num_fine_vertices)
        face, bary, _offset = self.proxy.fine_map
        self.face = np.asarray(face, np.int64)
        bary = np.asarray(bary, np.float64)
        corners = np.column_stack([1.0 - bary[:, 0] - bary[:, 1], bary[:, 0], bary[:, 1]])
        rides = self.face >= 0
        self.riding = np.full(self.num_fine, -1, np.int64)
        self.riding[rides] = self.triangles[self.face[rides], np.argmax(corners[rides], axis=1)]
        self.riding[self.fine] = np.arange(self.num_vertices)

    def pins(self, fine_pins):
        """(#Q,) int32 sorted proxy vertices pinned for the mesh's pinned ``fine_pins``."""
        riding = self.riding[np.asarray(fine_pins, np.int64)]
        return np.unique(riding[riding >= 0]).astype(np.int32)

    def fine_pin_targets(self, fine_pins, fine_rest, proxy_pins, proxy_targets, proxy_rest):
        """(#fine_pins, 3) float64 targets of the mesh's pins for the proxy's pins at ``proxy_targets``:
        each moved as the proxy pin it maps to moved (pins() chose it), so a pin the artist left alone
        stays exactly where it was and a dragged handle carries its whole part of the mesh's pins."""
        fine_pins, proxy_pins = np.asarray(fine_pins, np.int64), np.asarray(proxy_pins, np.int64)
        targets = np.asarray(fine_rest, np.float64)[fine_pins].copy()
        if not len(fine_pins) or not len(proxy_pins):
            return targets
        row = np.full(self.num_vertices, -1, np.int64)
        row[proxy_pins] = np.arange(len(proxy_pins))
        rows = row[np.maximum(self.riding[fine_pins], 0)]
        mapped = (self.riding[fine_pins] >= 0) & (rows >= 0)
        moved = np.asarray(proxy_targets, np.float64) - np.asarray(proxy_rest, np.float64)[proxy_pins]
        targets[mapped] += moved[rows[mapped]]
        return targets

    def face_weights(self, fine_triangles, fine_face_weights):
        """(#G, #slots) float32 proxy face weights for the mesh's per-triangle weights (#T, #slots)."""
        fine_face_weights = np.asarray(fine_face_weights, np.float64)
        slots = fine_face_weights.shape[1]
        fine_triangles = np.asarray(fine_triangles, np.int64)
        corners = fine_triangles.ravel()
        counts = np.maximum(np.bincount(corners, minlength=self.num_fine), 1)
        rides = self.face >= 0
        riders = np.bincount(self.face[rides], minlength=len(self.triangles)).astype(np.float64)
        out = np.empty((len(self.triangles), slots), np.float32)
        for slot in range(slots):
            per_vertex = np.bincount(corners, weights=np.repeat(fine_face_weights[:, slot], 3),
                                     minlength=self.num_fine) / counts
            sums = np.bincount(self.face[rides], weights=per_vertex[rides], minlength=len(self.triangles))
            corner_mean = per_vertex[self.fine[self.triangles]].mean(axis=1)
            out[:, slot] = np.where(riders > 0, sums / np.maximum(riders, 1.0), corner_mean)
        return out
