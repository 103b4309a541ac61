#pragma once
//! \file cgal_precompiled.h
//! \brief The CGAL headers most of the CGAL files include, precompiled once for all of them.
//! Parsing CGAL's kernel and Surface_mesh costs each translation unit that includes them about
//! ten seconds before it compiles a line of its own (gcc 12); precompiled, about one. Not
//! included by any source: the build passes it to the CGAL files (polycube_compile_cgal in the
//! top CMakeLists.txt).

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
