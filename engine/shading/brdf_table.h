// The BRDF's directional albedo under uniform light, tabulated once per
// process: the split of the environment term's Fresnel into the integrals of
// (1 - w) and w (w Schlick's weight; brdf_lanes.h FresnelSplit) over the GGX
// lobe, and the same for the diffuse lobe. Environment-independent.
//
// Entry (roughness row i, n.v column j), 3 floats:
//   A = integral of (1 - w) D V (n.l) dl,  B = integral of w D V (n.l) dl,
//   S = (1/pi) integral of w (n.l) dl over the hemisphere (the diffuse lobe's
//   Fresnel share, roughness-independent, repeated on every row),
// at roughness i / (kRoughnessCount - 1) (alpha = roughness^2) and
// n.v = (j + 0.5) / kNvCount. Rows i = 0 are exact (A = 1 - w(n.v), B = w(n.v)).
#pragma once

namespace quadra {

class Executor;

namespace brdf_table {
constexpr int kRoughnessCount = 32;
constexpr int kNvCount = 32;
constexpr int kEntryFloats = 3;
}  // namespace brdf_table

// The table, computed on first use (thread-safe; ~30 ms on 2 threads,
// in parallel over `executor`); the same bits for any thread count.
const float* brdfAlbedoTable(const Executor& executor);

}  // namespace quadra
