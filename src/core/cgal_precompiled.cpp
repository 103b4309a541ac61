//! The translation unit the CGAL headers are precompiled with (see cgal_precompiled.h).
#include "core/cgal_precompiled.h"
