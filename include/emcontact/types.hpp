#pragma once
// The only place naming Scalar/LO/GO/Node and the Tpetra aliases (Debian's Trilinos 13.2 has
// explicit instantiations only for <double, int, long long, Serial>: docs/developer-guide.md).
#include <Kokkos_Core.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_FECrsGraph.hpp>
#include <Tpetra_FECrsMatrix.hpp>
#include <Tpetra_FEMultiVector.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Vector.hpp>

namespace emc {
using Scalar = double;
using LO = int;
using GO = long long;
using Map = Tpetra::Map<LO, GO>;
using Node = Map::node_type;
using ExecSpace = Node::execution_space;
using MemSpace = Node::memory_space;
using Graph = Tpetra::CrsGraph<LO, GO, Node>;
using FEGraph = Tpetra::FECrsGraph<LO, GO, Node>;
using Matrix = Tpetra::CrsMatrix<Scalar, LO, GO, Node>;
using FEMatrix = Tpetra::FECrsMatrix<Scalar, LO, GO, Node>;
using Vector = Tpetra::Vector<Scalar, LO, GO, Node>;
using MultiVector = Tpetra::MultiVector<Scalar, LO, GO, Node>;
using Operator = Tpetra::Operator<Scalar, LO, GO, Node>;
using Import = Tpetra::Import<LO, GO, Node>;
using Export = Tpetra::Export<LO, GO, Node>;
using Comm = Teuchos::Comm<int>;
}  // namespace emc
