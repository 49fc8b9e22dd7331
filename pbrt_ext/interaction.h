// Surface interactions: what the integrator knows about a ray's hit (pbrt-v4's
// src/pbrt/interaction.h).
#pragma once

#include "pbrt_ext/base/bxdf.h"
#include "pbrt_ext/base/medium.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/ray.h"
#include "pbrt_ext/util/vecmath.h"

namespace pbrt {

// The geometry of a hit. n is the geometric normal, flipped by ReverseOrientation and transform
// handedness exactly as pbrt-v4 does; shading.n lies on the same side as n.
struct SurfaceInteraction {
    Point3f p;
    Normal3f n;
    Point2f uv;
    Vector3f wo;  // toward the ray origin, unit
    Vector3f dpdu, dpdv;
    struct {
        Normal3f n;
        Vector3f dpdu, dpdv;
        // How the shading normal turns across the surface (pbrt-v4's dndu, dndv), for bump
        // mapping: from the vertex normals of a mesh, dpdu / r on a sphere, zero where flat.
        Normal3f dndu, dndv;
    } shading;
    Float time = 0;           // the time of the ray that found it; rays leaving keep it
    Float errorBound = 0;     // how far p may be from the surface: a curve's width, else 0
    // The footprint of a pixel here: how p, u and v change from one pixel to the next on the
    // film (pbrt-v4's dpdx ... dvdy), for texture filtering and the bump map's step; zero
    // until SetDifferentials.
    Vector3f dpdx, dpdy;
    Float dudx = 0, dvdx = 0, dudy = 0, dvdy = 0;
    int materialIndex = -1;   // into Scene::materials; -1: no material (an interface)
    int areaLightIndex = -1;  // into Scene::lights; -1: not emissive
    // The media on either side: the shape's where it separates two media, else the ray's on
    // both sides (pbrt-v4's SetIntersectionProperties).
    MediumInterface mediumInterface;

    // dp/dx and dp/dy, and the (u, v) changes they mean: the least-squares solution of
    // dp = dp/du du + dp/dv dv (pbrt-v4's ComputeDifferentials), kept finite and within 1e8.
    PBRT_CPU_GPU void SetDifferentials(Vector3f dpdx_, Vector3f dpdy_) {
        dpdx = dpdx_;
        dpdy = dpdy_;
        Float ata00 = Dot(dpdu, dpdu), ata01 = Dot(dpdu, dpdv), ata11 = Dot(dpdv, dpdv);
        Float invDet = 1 / (ata00 * ata11 - ata01 * ata01);
        invDet = IsFinite(invDet) ? invDet : 0;
        auto solve = [&](Vector3f dp, Float *du, Float *dv) {
            Float atb0 = Dot(dpdu, dp), atb1 = Dot(dpdv, dp);
            *du = (ata11 * atb0 - ata01 * atb1) * invDet;
            *dv = (ata00 * atb1 - ata01 * atb0) * invDet;
            *du = IsFinite(*du) ? Clamp(*du, -1e8f, 1e8f) : 0;
            *dv = IsFinite(*dv) ? Clamp(*dv, -1e8f, 1e8f) : 0;
        };
        solve(dpdx, &dudx, &dvdx);
        solve(dpdy, &dudy, &dvdy);
    }
    // Where the ray's neighbours meet the tangent plane at p, when it has them.
    PBRT_CPU_GPU bool DifferentialsFrom(const RayDifferential &ray) {
        if (!ray.hasDifferentials || Dot(n, ray.rxDirection) == 0 || Dot(n, ray.ryDirection) == 0)
            return false;
        Float d = -Dot(n, Vector3f(p));
        Float tx = (-Dot(n, Vector3f(ray.rxOrigin)) - d) / Dot(n, ray.rxDirection);
        Float ty = (-Dot(n, Vector3f(ray.ryOrigin)) - d) / Dot(n, ray.ryDirection);
        SetDifferentials(ray.rxOrigin + tx * ray.rxDirection - p,
                         ray.ryOrigin + ty * ray.ryDirection - p);
        return true;
    }

    // The ray the BSDF sampled (direction wi, lobe flags, relative eta), with differentials
    // where the incoming ray had them and the bounce was a perfect mirror or refraction: the
    // neighbours reflected or refracted off the surface as it turns across the footprint
    // (pbrt-v4's SpawnRay with a BSDF, Igehy 1999). Other bounces spread the footprint past
    // what differentials describe; their hits use the camera's approximation.
    PBRT_CPU_GPU RayDifferential SpawnRay(const RayDifferential &rayi, Vector3f wi,
                                          BxDFFlags flags, Float eta) const {
        RayDifferential rd(SpawnRay(wi));
        bool reflect = flags == BxDFFlags::SpecularReflection;
        if (!rayi.hasDifferentials || (!reflect && flags != BxDFFlags::SpecularTransmission))
            return rd;
        Normal3f ns = shading.n;
        Normal3f dndx = shading.dndu * dudx + shading.dndv * dvdx;
        Normal3f dndy = shading.dndu * dudy + shading.dndv * dvdy;
        Vector3f dwodx = -rayi.rxDirection - wo, dwody = -rayi.ryDirection - wo;
        rd.rxOrigin = p + dpdx;
        rd.ryOrigin = p + dpdy;
        if (!reflect && Dot(wo, ns) < 0) {
            ns = -ns;
            dndx = -dndx;
            dndy = -dndy;
        }
        Float dwoDotn_dx = Dot(dwodx, ns) + Dot(wo, dndx);
        Float dwoDotn_dy = Dot(dwody, ns) + Dot(wo, dndy);
        if (reflect) {
            rd.rxDirection = wi - dwodx + 2 * Vector3f(Dot(wo, ns) * dndx + dwoDotn_dx * ns);
            rd.ryDirection = wi - dwody + 2 * Vector3f(Dot(wo, ns) * dndy + dwoDotn_dy * ns);
        } else {
            Float mu = Dot(wo, ns) / eta - AbsDot(wi, ns);
            Float k = 1 / eta + 1 / Sqr(eta) * Dot(wo, ns) / Dot(wi, ns);
            rd.rxDirection = wi - eta * dwodx + Vector3f(mu * dndx + dwoDotn_dx * k * ns);
            rd.ryDirection = wi - eta * dwody + Vector3f(mu * dndy + dwoDotn_dy * k * ns);
        }
        // Differentials this large describe no footprint any more.
        rd.hasDifferentials = LengthSquared(rd.rxDirection) <= 1e16f &&
                              LengthSquared(rd.ryDirection) <= 1e16f &&
                              LengthSquared(Vector3f(rd.rxOrigin)) <= 1e16f &&
                              LengthSquared(Vector3f(rd.ryOrigin)) <= 1e16f;
        return rd;
    }

    // Replaces the shading frame (pbrt-v4's SetShadingGeometry). Where the orientation is
    // authoritative (a mesh's vertex normals), n moves to ns's side; otherwise (a bump or normal
    // map) ns is turned to n's side. Tangents too large to take products of are scaled down.
    // dndu and dndv stay those of the unperturbed surface, as in pbrt-v4.
    PBRT_CPU_GPU void SetShadingGeometry(Normal3f ns, Vector3f dpdus, Vector3f dpdvs,
                                         bool orientationIsAuthoritative) {
        shading.n = ns;
        if (orientationIsAuthoritative)
            n = FaceForward(n, shading.n);
        else
            shading.n = FaceForward(shading.n, n);
        while (LengthSquared(dpdus) > 1e16f || LengthSquared(dpdvs) > 1e16f) {
            dpdus /= 1e8f;
            dpdvs /= 1e8f;
        }
        shading.dpdu = dpdus;
        shading.dpdv = dpdvs;
    }

    // The medium a ray leaving in direction w travels through.
    PBRT_CPU_GPU int GetMedium(Vector3f w) const {
        return Dot(w, Vector3f(n)) > 0 ? mediumInterface.outside : mediumInterface.inside;
    }
    // A ray leaving the surface in direction w, its origin offset to w's side.
    PBRT_CPU_GPU Ray SpawnRay(Vector3f w) const {
        return Ray(OffsetRayOrigin(p, n, w, errorBound), w, GetMedium(w), time);
    }
    // A ray toward the point p2 with d = p2 - o, so that t = 1 reaches it.
    PBRT_CPU_GPU Ray SpawnRayTo(Point3f p2) const {
        Point3f o = OffsetRayOrigin(p, n, p2 - p, errorBound);
        return Ray(o, p2 - o, GetMedium(p2 - p), time);
    }
};

// What a light needs to know about the point it illuminates (pbrt-v4's LightSampleContext).
struct LightSampleContext {
    LightSampleContext() = default;
    PBRT_CPU_GPU explicit LightSampleContext(const SurfaceInteraction &si)
        : p(si.p), n(si.n), ns(si.shading.n) {}
    PBRT_CPU_GPU LightSampleContext(Point3f p, Normal3f n, Normal3f ns) : p(p), n(n), ns(ns) {}

    Point3f p;
    Normal3f n, ns;  // zero for a point in free space
};

}  // namespace pbrt
