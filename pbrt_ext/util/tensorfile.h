// pbrt_ext: the "tensor file" of the RGL material database (Dupuy and Jakob 2018), the container
// of the .bsdf files pbrt-v4's measured material reads.
//
// Layout (little-endian): the 12 bytes "tensor_file\0", the version bytes 1 0, a uint32 field
// count, then per field: a uint16 name length and the name, a uint16 rank, a uint8 element type
// (TensorField::Type), a uint64 offset of its data from the file's start, and one uint64 size per
// dimension. The data are the elements, row-major, at those offsets.
//
// Reading checks everything a corrupt or hostile file could get wrong before anything is
// allocated for it: the header and version, names and ranks within bounds, sizes whose product
// does not overflow, data inside the file, no name twice; the file itself is read whole after
// the memory budget check (resourcelimits.h). Errors throw std::runtime_error
// "<path>: error: <what>".
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

namespace pbrt {

struct TensorField {
    // The element types, numbered as the format numbers them.
    enum class Type : uint8_t {
        UInt8 = 1,
        Int8,
        UInt16,
        Int16,
        UInt32,
        Int32,
        UInt64,
        Int64,
        Float16,
        Float32,
        Float64
    };
    Type type = Type::Float32;
    std::vector<uint64_t> shape;
    std::vector<uint8_t> bytes;  // the elements, row-major

    uint64_t Count() const;
    // The elements as T, which must match the type (Float32: float, UInt8: uint8_t).
    std::span<const float> Floats() const;
    std::span<const uint8_t> UInt8s() const;

    static TensorField FromFloats(std::vector<uint64_t> shape, const std::vector<float> &values);
    static TensorField FromBytes(std::vector<uint64_t> shape, const std::vector<uint8_t> &values);
};

// The size in bytes of one element of type t; 0 for a number that names no type.
size_t TensorElementSize(uint8_t type);

using TensorFields = std::map<std::string, TensorField>;

TensorFields ReadTensorFile(const std::string &path);
// Written atomically (atomicfile.h); throws std::runtime_error on failure.
void WriteTensorFile(const std::string &path, const TensorFields &fields);

}  // namespace pbrt
