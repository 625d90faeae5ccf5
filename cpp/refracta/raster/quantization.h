// Storage of 4 power moments as a GPU would keep them: fp32, or 16-bit UNORM after the optimised
// quantisation transforms (MOMENTS.md 2.5): the dense affine transform of Peters & Klein (I3D
// 2015) for depths in [0, 1], and the sparse transform Theta*_4 of Peters et al. (JCGT 2017) for
// depths in [-1, 1]. Decoding the stored value gives the moments a shader would read back.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace refracta {

using Moments4 = std::array<double, 4>;

// How moments are kept, by shadow maps and by MBOIT alike: fp64 (no storage error), fp32, or
// 16-bit UNORM through the optimised transforms (MBOIT takes fp32 and unorm16).
enum class Storage { kFp64, kFp32, kUnorm16 };
Storage parse_storage(const std::string& name);  // "fp64", "fp32", "unorm16"
const char* storage_name(Storage storage);

// The depth range moments are computed over: [0, 1] (Peters & Klein, I3D 2015) or [-1, 1]
// (Peters et al., JCGT 2017).
enum class DepthRange { kUnit, kSigned };
DepthRange parse_depth_range(const std::string& name);  // "unit", "signed"
const char* depth_range_name(DepthRange range);

// q = A b + offset, the optimised transform (signed: Theta*_4); every q of a depth in range lies in [0, 1]^4.
Moments4 quantization_transform(const Moments4& b, bool signed_depth);
Moments4 inverse_quantization_transform(const Moments4& q, bool signed_depth);
// b as read back after storage (unorm16: transform, round to 16 bits, inverse transform).
Moments4 stored_moments(const Moments4& b, Storage storage, bool signed_depth);

// MBOIT's 16-bit (ROV) storage of 6 or 8 normalised power moments b_1..b_m of depths in [-1, 1]
// (Muenstermann et al. 2018, supplementary shader code): odd and even moments each mapped into
// [0, 1] by a fixed matrix and offset, rounded to 16 bits, mapped back (exact inverse).
std::vector<double> stored_mboit_unorm16(const std::vector<double>& b);

}  // namespace refracta
