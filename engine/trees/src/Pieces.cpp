#include <sylva/trees/Pieces.hpp>

#include "internal/Skinning.hpp"

#include <sylva/core/Error.hpp>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <queue>

namespace sylva::trees {
namespace {

using Ring = std::array<std::uint32_t, kRimCorners>;

const float kTanCone = std::tan(kRimConeAngle);

/** Builds a piece: rings of six vertices in rim-like frames, bands of quads, free vertices, then orients. */
class Builder {
public:
  explicit Builder(std::string name) { mPiece.name = std::move(name); }

  /** A rim: leaf rims get the next joint. Frame: standard rim frame → model space. */
  Ring rim(const glm::mat4& frame) {
    const int index = static_cast<int>(mPiece.rims.size());
    Rim r;
    r.frame = frame;
    r.joint = index;
    for (int k = 0; k < kRimCorners; ++k) {
      PieceVertex v;
      v.rim = index;
      v.corner = k;
      v.joints = {static_cast<std::uint8_t>(index), 0, 0, 0};
      r.vertices[static_cast<std::size_t>(k)] = add(v);
    }
    mPiece.rims.push_back(r);
    mPiece.joints.push_back(Joint{frame, index});
    return r.vertices;
  }

  /** A ring of six free vertices: corner k of the hexagon of `radius` at height `y`, in `frame`. */
  Ring ring(const glm::mat4& frame, float y, float radius) {
    Ring out{};
    for (int k = 0; k < kRimCorners; ++k) {
      out[static_cast<std::size_t>(k)] =
          point(glm::vec3(frame * glm::vec4(rimCorner(k) * radius + glm::vec3(0, y, 0), 1.0f)));
    }
    return out;
  }

  std::uint32_t point(const glm::vec3& p) {
    PieceVertex v;
    v.position = p;
    return add(v);
  }

  /**
   * A vertex whose normal is given rather than averaged from its quads: crotch and pit vertices, where the
   * surface turns too sharply for averaging (Phong tessellation would fold there).
   */
  std::uint32_t point(const glm::vec3& p, const glm::vec3& normal) {
    const std::uint32_t i = point(p);
    mFixedNormals.emplace_back(i, glm::normalize(normal));
    return i;
  }

  /** Quads between two rings with corners aligned (corner k to corner k). */
  void band(const Ring& a, const Ring& b, std::uint8_t tileClass = 0) {
    for (int k = 0; k < kRimCorners; ++k) {
      const auto k0 = static_cast<std::size_t>(k);
      const auto k1 = static_cast<std::size_t>((k + 1) % kRimCorners);
      quad(a[k0], a[k1], b[k1], b[k0], tileClass);
    }
  }

  void quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d, std::uint8_t tileClass = 0) {
    mPiece.quads.push_back({a, b, c, d});
    mPiece.tileClass.push_back(tileClass);
  }

  /** Finishes: rim positions exact, orientation consistent and outward, normals, skinning weights. */
  Piece finish(bool bearsFoliage) {
    mPiece.bearsFoliage = bearsFoliage;
    snapRims(mPiece);
    orient();
    computeNormals(mPiece);
    for (const auto& [i, n] : mFixedNormals) {
      mPiece.vertices[i].normal = n;
    }
    weights();
    validatePiece(mPiece, "built-in pieces");
    return std::move(mPiece);
  }

private:
  std::uint32_t add(const PieceVertex& v) {
    mPiece.vertices.push_back(v);
    return static_cast<std::uint32_t>(mPiece.vertices.size() - 1);
  }

  /**
   * Makes adjacent quads traverse their shared edge in opposite directions (breadth-first from quad 0), then
   * turns everything over if the root rim's band faces inwards.
   */
  void orient() {
    auto& quads = mPiece.quads;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::size_t>> byEdge;
    auto key = [](std::uint32_t a, std::uint32_t b) {
      return std::make_pair(std::min(a, b), std::max(a, b));
    };
    for (std::size_t q = 0; q < quads.size(); ++q) {
      for (int e = 0; e < 4; ++e) {
        byEdge[key(quads[q][static_cast<std::size_t>(e)], quads[q][static_cast<std::size_t>((e + 1) % 4)])]
            .push_back(q);
      }
    }
    std::vector<bool> done(quads.size(), false);
    std::queue<std::size_t> open;
    open.push(0);
    done[0] = true;
    auto hasDirected = [&](std::size_t q, std::uint32_t a, std::uint32_t b) {
      for (int e = 0; e < 4; ++e) {
        if (quads[q][static_cast<std::size_t>(e)] == a &&
            quads[q][static_cast<std::size_t>((e + 1) % 4)] == b) {
          return true;
        }
      }
      return false;
    };
    while (!open.empty()) {
      const std::size_t q = open.front();
      open.pop();
      for (int e = 0; e < 4; ++e) {
        const std::uint32_t a = quads[q][static_cast<std::size_t>(e)];
        const std::uint32_t b = quads[q][static_cast<std::size_t>((e + 1) % 4)];
        for (std::size_t other : byEdge[key(a, b)]) {
          if (other == q || done[other]) {
            continue;
          }
          if (hasDirected(other, a, b)) {
            std::reverse(quads[other].begin(), quads[other].end());
          }
          done[other] = true;
          open.push(other);
        }
      }
    }
    // Outward: a quad touching the root rim must face away from the axis.
    for (std::size_t q = 0; q < quads.size(); ++q) {
      const auto& v = mPiece.vertices;
      if (v[quads[q][0]].rim != 0 && v[quads[q][1]].rim != 0) {
        continue;
      }
      glm::vec3 centre(0.0f);
      for (std::uint32_t i : quads[q]) {
        centre += v[i].position * 0.25f;
      }
      const glm::vec3 n = glm::cross(v[quads[q][2]].position - v[quads[q][0]].position,
                                     v[quads[q][3]].position - v[quads[q][1]].position);
      if (glm::dot(n, glm::vec3(centre.x, 0.0f, centre.z)) < 0.0f) {
        for (auto& quad : quads) {
          std::reverse(quad.begin(), quad.end());
        }
      }
      break;
    }
  }

  /**
   * Skinning weights of free vertices: blend between the root joint and the nearest terminal joint by where
   * the vertex lies between the root rim and that leaf rim (smoothstep), so bends spread along the piece.
   */
  void weights() { internal::blendInteriorWeights(mPiece); }

  Piece mPiece;
  std::vector<std::pair<std::uint32_t, glm::vec3>> mFixedNormals;
};

glm::mat4 frameAt(const glm::vec3& origin, const glm::mat4& rotation, float scale) {
  return glm::translate(glm::mat4(1.0f), origin) * rotation * glm::scale(glm::mat4(1.0f), glm::vec3(scale));
}

/** Rotation tilting +y by `tilt` radians towards the horizontal direction at `azimuth` (x towards z). */
glm::mat4 tiltTowards(float azimuth, float tilt) {
  const glm::vec3 towards(std::cos(azimuth), 0.0f, std::sin(azimuth));
  const glm::vec3 axis = glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), towards);
  if (tilt == 0.0f) {
    return glm::mat4(1.0f);
  }
  return glm::rotate(glm::mat4(1.0f), tilt, glm::normalize(axis));
}

/** The ring just inside a leaf rim (in the rim's frame at −depth), on the fixed cone. */
Ring innerRing(Builder& b, const glm::mat4& leafFrame, float depth) {
  return b.ring(leafFrame, -depth, 1.0f + depth * kTanCone);
}

/**
 * A two-way fork over the ring `base` (corners 0 … 5): child P leans to +z, child Q to −z. Crotch vertices c+
 * (towards +x) and c− (towards −x) join them. Quads per child: outer, two sides, two crotch, one inner.
 */
void fork(Builder& b, const Ring& base, const Ring& p, const Ring& q, const glm::vec3& cPlus,
          const glm::vec3& cMinus, float crotchLean) {
  // The crotch vertices sit where the valley between the children meets the sides: outwards and up, leaning
  // towards the side branch when the children differ.
  const std::uint32_t cp = b.point(cPlus, glm::vec3(1.0f, 1.0f, crotchLean));
  const std::uint32_t cm = b.point(cMinus, glm::vec3(-1.0f, 1.0f, crotchLean));
  // P (towards +z): base corners 1, 2 face it; its corners 4, 5 face the crotch.
  b.quad(base[1], base[2], p[2], p[1], 1);
  b.quad(base[0], base[1], p[1], p[0], 1);
  b.quad(base[2], base[3], p[3], p[2], 1);
  b.quad(base[0], cp, p[5], p[0], 2);
  b.quad(base[3], cm, p[4], p[3], 2);
  b.quad(cp, cm, p[4], p[5], 2);
  // Q (towards −z): base corners 4, 5 face it; its corners 1, 2 face the crotch.
  b.quad(base[4], base[5], q[5], q[4], 1);
  b.quad(base[3], base[4], q[4], q[3], 1);
  b.quad(base[5], base[0], q[0], q[5], 1);
  b.quad(base[0], cp, q[1], q[0], 2);
  b.quad(base[3], cm, q[2], q[3], 2);
  b.quad(cp, cm, q[2], q[1], 2);
}

/** A two-child fork piece: root rim, a cone band, the fork, and a cone band under each leaf rim. */
Piece twoWay(const std::string& name, const glm::mat4& pFrame, const glm::mat4& qFrame, float crotchHeight,
             float crotchX, float crotchZ, float crotchLean) {
  Builder b(name);
  const Ring root = b.rim(glm::mat4(1.0f));
  const Ring p = b.rim(pFrame);
  const Ring q = b.rim(qFrame);
  const float h1 = 0.4f;
  const Ring lower = b.ring(glm::mat4(1.0f), h1, 1.0f - h1 * kTanCone);
  b.band(root, lower);
  const float depth = 0.35f;
  const Ring pIn = innerRing(b, pFrame, depth);
  const Ring qIn = innerRing(b, qFrame, depth);
  b.band(pIn, p);
  b.band(qIn, q);
  fork(b, lower, pIn, qIn, glm::vec3(crotchX, crotchHeight, crotchZ),
       glm::vec3(-crotchX, crotchHeight, crotchZ), crotchLean);
  return b.finish(false);
}

} // namespace

Piece makeI() {
  Builder b("I");
  // Branch segments are much longer than they are thick: 5 rim radii.
  const float length = 5.0f;
  const float scale = 1.0f - length * kTanCone;
  const Ring root = b.rim(glm::mat4(1.0f));
  const Ring leaf = b.rim(frameAt(glm::vec3(0.0f, length, 0.0f), glm::mat4(1.0f), scale));
  const float third = length / 3.0f;
  const Ring r1 = b.ring(glm::mat4(1.0f), third, 1.0f - third * kTanCone);
  const Ring r2 = b.ring(glm::mat4(1.0f), 2.0f * third, 1.0f - 2.0f * third * kTanCone);
  b.band(root, r1);
  b.band(r1, r2);
  b.band(r2, leaf);
  return b.finish(false);
}

Piece makeY() {
  const float tilt = 0.52f; // 30°
  const float scale = 0.72f;
  const glm::mat4 p =
      frameAt(glm::vec3(0.0f, 2.4f, 0.95f), tiltTowards(std::numbers::pi_v<float> / 2, tilt), scale);
  const glm::mat4 q =
      frameAt(glm::vec3(0.0f, 2.4f, -0.95f), tiltTowards(-std::numbers::pi_v<float> / 2, tilt), scale);
  return twoWay("Y", p, q, 1.7f, 0.5f, 0.0f, 0.0f);
}

Piece makeBranch() {
  // The stem continues almost straight (P, leaning slightly away from the side branch); the side branch Q
  // leaves low and steep.
  const glm::mat4 p =
      frameAt(glm::vec3(0.0f, 2.4f, 0.35f), tiltTowards(std::numbers::pi_v<float> / 2, 0.06f), 0.85f);
  const glm::mat4 q =
      frameAt(glm::vec3(0.0f, 1.45f, -1.05f), tiltTowards(-std::numbers::pi_v<float> / 2, 1.01f), 0.5f);
  return twoWay("Branch", p, q, 1.4f, 0.5f, -0.45f, -0.22f);
}

Piece makePsi() {
  Builder b("Psi");
  const Ring root = b.rim(glm::mat4(1.0f));
  const float tilt = 0.61f; // 35°
  const float scale = 0.62f;
  std::array<glm::mat4, 3> frames{};
  std::array<Ring, 3> leaves{};
  for (int c = 0; c < 3; ++c) {
    // Child c leans towards corner 2c + 1 (azimuth 60° + 120°c); its own corner 0 points outwards.
    const float azimuth = std::numbers::pi_v<float> / 3.0f * static_cast<float>(2 * c + 1);
    const glm::vec3 out(std::cos(azimuth), 0.0f, std::sin(azimuth));
    frames[static_cast<std::size_t>(c)] = frameAt(glm::vec3(0.0f, 2.2f, 0.0f) + out * 0.95f,
                                                  tiltTowards(azimuth, tilt) * rimRotation(2 * c + 1), scale);
    leaves[static_cast<std::size_t>(c)] = b.rim(frames[static_cast<std::size_t>(c)]);
  }
  const float h1 = 0.4f;
  const Ring lower = b.ring(glm::mat4(1.0f), h1, 1.0f - h1 * kTanCone);
  b.band(root, lower);
  std::array<Ring, 3> inner{};
  for (std::size_t c = 0; c < 3; ++c) {
    inner[c] = innerRing(b, frames[c], 0.35f);
    b.band(inner[c], leaves[c]);
  }
  // Crotch vertices above base corners 0, 2, 4 (between the children) and one at the centre.
  std::array<std::uint32_t, 3> crotch{};
  for (int c = 0; c < 3; ++c) {
    const float azimuth = std::numbers::pi_v<float> / 3.0f * static_cast<float>(2 * c);
    const glm::vec3 out(std::cos(azimuth), 0.0f, std::sin(azimuth));
    crotch[static_cast<std::size_t>(c)] =
        b.point(out * 0.6f + glm::vec3(0.0f, 1.5f, 0.0f), out + glm::vec3(0.0f, 1.0f, 0.0f));
  }
  // The centre of the three valleys: a saddle-like top facing up.
  const std::uint32_t centre = b.point(glm::vec3(0.0f, 1.85f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
  for (int c = 0; c < 3; ++c) {
    // Child c faces base corner m = 2c + 1 with its corner 0; base corners m − 1 and m + 1 hold the crotch
    // vertices before and after it.
    const auto& a = inner[static_cast<std::size_t>(c)];
    const auto m = static_cast<std::size_t>(2 * c + 1);
    const std::uint32_t before = crotch[static_cast<std::size_t>(c)];
    const std::uint32_t after = crotch[static_cast<std::size_t>((c + 1) % 3)];
    b.quad(lower[m - 1], lower[m], a[0], a[5], 1);
    b.quad(lower[m], lower[(m + 1) % 6], a[1], a[0], 1);
    b.quad(lower[(m + 1) % 6], after, a[2], a[1], 2);
    b.quad(before, lower[m - 1], a[5], a[4], 2);
    b.quad(after, centre, a[3], a[2], 2);
    b.quad(centre, before, a[4], a[3], 2);
  }
  return b.finish(false);
}

Piece makeCap() {
  // A twig tip tapering to a point, since a rounded stub reads as a finger. Like every piece, it continues
  // the rim's cone for half a radius. Then come rings at 60 %, 20 % and 6 % of the radius (the last one
  // keeps Phong tessellation from rounding the point) and three quads meeting at the tip on the axis.
  // The cross-section at 95 % of the length is under 5 % of the rim's.
  Builder b("Cap");
  const Ring root = b.rim(glm::mat4(1.0f));
  const Ring r1 = b.ring(glm::mat4(1.0f), 0.5f, 1.0f - 0.5f * kTanCone);
  const Ring r2 = b.ring(glm::mat4(1.0f), 1.6f, 0.6f);
  const Ring r3 = b.ring(glm::mat4(1.0f), 2.6f, 0.2f);
  const Ring r4 = b.ring(glm::mat4(1.0f), 3.0f, 0.06f);
  const std::uint32_t tip = b.point(glm::vec3(0.0f, kCapLength, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
  b.band(root, r1, 3);
  b.band(r1, r2, 3);
  b.band(r2, r3, 3);
  b.band(r3, r4, 3);
  for (std::size_t k = 0; k < 6; k += 2) {
    b.quad(tip, r4[k], r4[k + 1], r4[(k + 2) % 6], 3);
  }
  return b.finish(true);
}

Piece makeFoot() {
  Builder b("Foot");
  const Ring root = b.rim(glm::mat4(1.0f));
  const float top = 1.6f;
  const float scale = 0.8f;
  const Ring leaf = b.rim(frameAt(glm::vec3(0.0f, top, 0.0f), glm::mat4(1.0f), scale));
  const Ring r1 = b.ring(glm::mat4(1.0f), 0.3f, 1.0f - 0.3f * kTanCone);
  const Ring r2 = b.ring(glm::mat4(1.0f), 0.8f, 0.86f);
  const Ring r3 = innerRing(b, frameAt(glm::vec3(0.0f, top, 0.0f), glm::mat4(1.0f), scale), 0.3f);
  b.band(root, r1, 4);
  b.band(r1, r2, 4);
  b.band(r2, r3, 4);
  b.band(r3, leaf, 4);
  // Closed underneath: a bevelled ring, then three quads around a centre facing down.
  const Ring below = b.ring(glm::mat4(1.0f), -0.12f, 1.0f + 0.12f * kTanCone);
  const Ring bevel = b.ring(glm::mat4(1.0f), -0.3f, 0.8f);
  b.band(below, root, 4);
  b.band(bevel, below, 4);
  const std::uint32_t bottom = b.point(glm::vec3(0.0f, -0.36f, 0.0f), glm::vec3(0.0f, -1.0f, 0.0f));
  for (std::size_t k = 0; k < 6; k += 2) {
    b.quad(bottom, bevel[(k + 2) % 6], bevel[k + 1], bevel[k], 4);
  }
  return b.finish(false);
}

int PieceSet::find(const std::string& name) const {
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if (pieces[i].name == name) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

int PieceSet::require(const std::string& name, const std::string& where) const {
  const int i = find(name);
  if (i < 0) {
    std::string known;
    for (const Piece& p : pieces) {
      known += (known.empty() ? "" : ", ") + p.name;
    }
    fail("{}: unknown piece '{}' (known: {})", where, name, known);
  }
  return i;
}

PieceSet standardPieces() {
  PieceSet set;
  set.pieces = {makeI(), makeY(), makePsi(), makeBranch(), makeCap(), makeFoot()};
  return set;
}

} // namespace sylva::trees
