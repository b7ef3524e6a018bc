// Indexed triangle mesh in object space.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"

namespace tandem {

struct Mesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;      // per vertex, unit; same count as positions
  std::vector<Vec4> tangents;     // xyz unit, w = bitangent sign; same count as positions
  std::vector<Vec2> uvs;          // same count as positions (zeros when the source has none)
  std::vector<uint32_t> indices;  // 3 per triangle

  size_t triangleCount() const { return indices.size() / 3; }
  size_t memoryBytes() const;
};

// Removes triangles with repeated indices or zero area; returns how many were removed.
size_t removeDegenerateTriangles(Mesh& m);
// Area-weighted smooth normals, split where adjacent faces differ by more than creaseDeg
// (so a box stays faceted while a scanned bunny is smooth). May duplicate vertices.
void computeNormals(Mesh& m, float creaseDeg = 60.0f);
// Per-vertex tangents from UV derivatives (Lengyel's method), Gram-Schmidt against normals.
void computeTangents(Mesh& m);
// Tangents built as MikkTSpace builds them (glTF's rule for normal-mapped meshes without
// TANGENT): angle-weighted dP/du projected per corner onto the vertex normal's plane, summed per
// UV orientation (a vertex used by both orientations is split). Needs normals and UVs.
void computeMikkTSpaceTangents(Mesh& m);
// Fills missing attributes (normals, tangents, uvs) so every mesh is complete.
void completeMesh(Mesh& m);

}  // namespace tandem
