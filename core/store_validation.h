// The one-time check of an untrusted blob: everything a query will later trust.
#pragma once

#include "core/store_impl.h"

#include <cstddef>
#include <cstdint>

namespace tetprobe {

// Validates a blob held in aligned memory (size bytes, all readable): header, section table,
// checksum, probes, every cell vertex and grid index, and (fast layout) every neighbour index
// against its count; and refuses what the builder never writes: an origin or positions beyond its
// coordinate limits (coordinate_limits.h), bounds other than the positions' bounding box, normals
// with a component outside [-1, 1]. Throws Error(Status::invalid_blob) naming the first problem found, or
// Error(Status::version) for a well-formed blob of another format version (formats 2 and 3 included).
// Reads nothing outside [data, data + size).
void validate_store_blob(const uint8_t* data, size_t size);

// Validates the cell records of a loaded store (the blob's, or those rebuilt from a compact blob):
// every neighbour is a cell of the right kind that lists the cell back across the same facet (it
// holds every vertex of the facet), and every inner cell is oriented positively or, a tetrahedron
// only, is flat (exact orientation on the stored positions; a line's or flat set's cell of zero
// length or area in its axis's coordinates means an axis that does not match the positions).
// Throws Error(Status::invalid_blob).
void validate_cell_records(const Store::Impl& store);

}  // namespace tetprobe
