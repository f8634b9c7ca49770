#pragma once
// A 2D constrained Delaunay triangulation (CGAL, exact predicates, inexact constructions) whose
// vertices carry an int and whose faces carry their nesting level, and the flood fill that sets
// it: for triangulating regions bounded by closed loops (section pieces, cap regions). Included
// only by translation units that already pay for CGAL's triangulation headers.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <list>

namespace ps::cdt {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
struct FaceInfo {
  int nesting = -1;
};
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Fbb = CGAL::Triangulation_face_base_with_info_2<FaceInfo, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K, Fbb>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;

// Nesting level of every face by flood fill from the infinite face (level 0), crossing a
// constraint increments the level: with the loops as constraints, odd levels are inside.
inline void mark_domains(CDT& cdt) {
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info().nesting = -1;
  std::list<CDT::Edge> border;
  auto fill = [&](CDT::Face_handle start, int level) {
    std::list<CDT::Face_handle> queue{start};
    while (!queue.empty()) {
      CDT::Face_handle fh = queue.front();
      queue.pop_front();
      if (fh->info().nesting != -1) continue;
      fh->info().nesting = level;
      for (int i = 0; i < 3; ++i) {
        CDT::Edge e(fh, i);
        CDT::Face_handle n = fh->neighbor(i);
        if (n->info().nesting == -1) {
          if (cdt.is_constrained(e))
            border.push_back(e);
          else
            queue.push_back(n);
        }
      }
    }
  };
  fill(cdt.infinite_face(), 0);
  while (!border.empty()) {
    CDT::Edge e = border.front();
    border.pop_front();
    CDT::Face_handle n = e.first->neighbor(e.second);
    if (n->info().nesting == -1) fill(n, e.first->info().nesting + 1);
  }
}

}  // namespace ps::cdt
