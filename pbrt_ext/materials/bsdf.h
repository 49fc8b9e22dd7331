// BSDF: a BxDF placed in the world by a shading frame (pbrt-v4's src/pbrt/bsdf.h). Directions in and
// out are in render (world) space; the BxDF sees the local frame with z = shading normal, x = dpdu.
#pragma once

#include "pbrt_ext/bxdfs/bxdfs.h"
#include "pbrt_ext/util/vecmath.h"

namespace pbrt {

class BSDF {
  public:
    // dpdus need not be perpendicular to ns: the frame keeps its component in the tangent plane,
    // or any tangent when it has none (pbrt-v4 orthogonalizes it the same way).
    BSDF(Normal3f ns, Vector3f dpdus, BxDF bxdf) : bxdf(std::move(bxdf)) {
        Vector3f z = Normalize(Vector3f(ns)), x = dpdus - Dot(dpdus, z) * z;
        Float len = Length(x);
        shadingFrame = len > 0 && IsFinite(len) ? Frame::FromXZ(x / len, z) : Frame::FromZ(z);
    }

    BxDFFlags Flags() const { return bxdf.Flags(); }
    Vector3f RenderToLocal(Vector3f v) const { return shadingFrame.ToLocal(v); }
    Vector3f LocalToRender(Vector3f v) const { return shadingFrame.FromLocal(v); }

    SampledSpectrum f(Vector3f woRender, Vector3f wiRender,
                      TransportMode mode = TransportMode::Radiance) const {
        Vector3f wi = RenderToLocal(wiRender), wo = RenderToLocal(woRender);
        if (wo.z == 0)
            return {};
        return bxdf.f(wo, wi, mode);
    }

    pstd::optional<BSDFSample> Sample_f(
        Vector3f woRender, Float u, Point2f u2, TransportMode mode = TransportMode::Radiance,
        BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const {
        Vector3f wo = RenderToLocal(woRender);
        if (wo.z == 0 || !(BxDFReflTransFlags(int(bxdf.Flags())) & sampleFlags))
            return {};
        pstd::optional<BSDFSample> bs = bxdf.Sample_f(wo, u, u2, mode, sampleFlags);
        if (!bs || !bs->f || !(bs->pdf > 0) || bs->wi.z == 0)
            return {};
        bs->wi = LocalToRender(bs->wi);
        return bs;
    }

    Float PDF(Vector3f woRender, Vector3f wiRender, TransportMode mode = TransportMode::Radiance,
              BxDFReflTransFlags sampleFlags = BxDFReflTransFlags::All) const {
        Vector3f wo = RenderToLocal(woRender), wi = RenderToLocal(wiRender);
        if (wo.z == 0)
            return 0;
        return bxdf.PDF(wo, wi, mode, sampleFlags);
    }

    void Regularize() { bxdf.Regularize(); }
    // The directional albedo toward woRender, estimated from the samples uc and u2.
    SampledSpectrum rho(Vector3f woRender, pstd::span<const Float> uc, pstd::span<const Point2f> u2) const {
        return bxdf.rho(RenderToLocal(woRender), uc, u2);
    }
    std::string ToString() const { return "[ BSDF bxdf: " + bxdf.ToString() + " ]"; }

  private:
    BxDF bxdf;
    Frame shadingFrame;
};

}  // namespace pbrt
