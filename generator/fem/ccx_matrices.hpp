// SPDX-License-Identifier: GPL-2.0-or-later
// Stiffness and mass matrices that CalculiX writes with
// `*FREQUENCY, SOLVER=MATRIXSTORAGE` (issue 38): jobname.sti and jobname.mas,
// one entry a line, "row column value", 1-based, the upper triangle (row <=
// column) column by column, explicit zeros included; and jobname.dof, line k
// naming row/column k as "node.direction" (direction 1, 2, 3: x, y, z).
// Dofs the job's *BOUNDARY holds are not in the files.
//
// The files are untrusted input: every defect (a missing file, a line that is
// not three numbers, an index out of range, an entry given twice, the two
// triangles disagreeing, a dof listed twice) is a model::ModelError naming the
// file, the line and the fix; nothing of their text is kept but the numbers.
#pragma once

#include <Eigen/SparseCore>
#include <string>
#include <vector>

namespace kanegen::fem {

/// Row/column k of the matrices: a node of the mesh and a translation.
struct CcxDof {
  int node = 0;       ///< the mesh's node id
  int direction = 0;  ///< 1, 2, 3: x, y, z
};

/// The .dof file: one dof a line.
std::vector<CcxDof> read_ccx_dofs(const std::string& path);

/// A .sti or .mas file of `n` rows (the .dof file's lines): n x n, both
/// triangles stored. A lower-triangle entry is accepted and mirrored; an entry
/// given in both triangles must agree to 1e-9 relative. Every diagonal entry
/// must be given and positive (a file cut short lacks the last ones).
Eigen::SparseMatrix<double> read_ccx_matrix(const std::string& path, int n);

}  // namespace kanegen::fem
