#pragma once
// Curved triangle meshes for tests, written as OBJ text: a closed sphere
// shell (subdivided icosahedron), an open spherical cap (a grid lifted
// onto a sphere) and a sheet creased along a line.
#include <array>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace atssim::test {

struct ObjMesh {
  std::vector<std::array<double, 3>> v;
  std::vector<std::array<int, 3>> f;

  std::string obj_text() const {
    std::ostringstream out;
    out.precision(17);
    for (const auto& p : v) out << "v " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
    for (const auto& t : f) out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
    return out.str();
  }
};

// A sphere of `radius` centred on the origin: an icosahedron subdivided
// `levels` times (level 2: 162 vertices, 320 triangles).
inline ObjMesh icosphere(double radius, int levels) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  ObjMesh m;
  m.v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
         {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  m.f = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
         {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
         {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  const auto normalize = [&](std::array<double, 3>& p) {
    const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    for (double& c : p) c *= radius / n;
  };
  for (auto& p : m.v) normalize(p);
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    const auto midpoint = [&](int a, int b) {
      const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      std::array<double, 3> p{};
      for (int k = 0; k < 3; ++k) p[k] = 0.5 * (m.v[a][k] + m.v[b][k]);
      normalize(p);
      m.v.push_back(p);
      return mid[key] = static_cast<int>(m.v.size()) - 1;
    };
    std::vector<std::array<int, 3>> faces;
    for (const auto& f : m.f) {
      const int a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
      faces.push_back({f[0], a, c});
      faces.push_back({f[1], b, a});
      faces.push_back({f[2], c, b});
      faces.push_back({a, b, c});
    }
    m.f = std::move(faces);
  }
  return m;
}

// An open cap of a sphere of radius `radius`: an n × n grid over
// [-half, half]² in xz, lifted to y = sqrt(R² − x² − z²) − R (doubly curved).
inline ObjMesh spherical_cap(double radius, double half, int n) {
  ObjMesh m;
  for (int k = 0; k < n; ++k) {
    for (int i = 0; i < n; ++i) {
      const double x = half * (2.0 * i / (n - 1) - 1.0), z = half * (2.0 * k / (n - 1) - 1.0);
      m.v.push_back({x, std::sqrt(radius * radius - x * x - z * z) - radius, z});
    }
  }
  for (int k = 0; k + 1 < n; ++k) {
    for (int i = 0; i + 1 < n; ++i) {
      const int a = k * n + i, b = a + 1, c = a + n, d = c + 1;
      m.f.push_back({a, c, b});
      m.f.push_back({b, c, d});
    }
  }
  return m;
}

// A square sheet of side 2 `half`, n × n vertices (n odd), creased along
// its middle row: the half s ≥ 0 flat at y = `lift` over z = s, the half
// s < 0 rising from the crease at `lean` radians over the flat half (the
// sheet folded open like a book). Rows run along the unfolded sheet, s from
// -half to half; the quads' diagonals alternate.
inline ObjMesh creased_sheet(double half, int n, double lean, double lift) {
  ObjMesh m;
  for (int j = 0; j < n; ++j) {
    const double s = half * (2.0 * j / (n - 1) - 1.0);
    for (int i = 0; i < n; ++i) {
      const double x = half * (2.0 * i / (n - 1) - 1.0);
      if (s >= 0) {
        m.v.push_back({x, lift, s});
      } else {
        m.v.push_back({x, lift - s * std::sin(lean), -s * std::cos(lean)});
      }
    }
  }
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i, b = a + 1, c = a + n + 1, d = a + n;
      if ((i + j) % 2 == 0) {
        m.f.push_back({a, b, c});
        m.f.push_back({a, c, d});
      } else {
        m.f.push_back({a, b, d});
        m.f.push_back({b, c, d});
      }
    }
  }
  return m;
}

}  // namespace atssim::test
