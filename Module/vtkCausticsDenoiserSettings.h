/**
 * @file   vtkCausticsDenoiserSettings.h
 * @brief  The knobs of the SVGF denoiser of caustic irradiance, as one value (not wrapped).
 *
 * vtkCausticsSVGFDenoiser owns one DenoiserSettings; its Set/Get methods (documented,
 * with their ranges, on the class) write into it, and its steps take it by const
 * reference when they run. Defaults are those of SVGF (Schied et al. 2017, cited by
 * 002_97e66a5090de9b07.txt §3.3) where SVGF has the knob; the others are this
 * module's (history rejection by colour, camera cuts), measured in docs/denoising.md.
 */
#ifndef vtkCausticsDenoiserSettings_h
#define vtkCausticsDenoiserSettings_h

#include "vtkCausticsSettingMacros.h" // For vtkCausticsSettingMacro (used with this struct)

namespace caustics
{
struct DenoiserSettings
{
  /** Weight of this frame in the colour history once it is long, [0.01, 1] (SVGF 0.2). */
  double TemporalAlpha = 0.2;
  /** Weight of this frame in the moments history once it is long, [0.01, 1] (SVGF 0.2). */
  double MomentsAlpha = 0.2;
  /** Frames a history counts at most (the blend weight is max(alpha, 1/n)), [1, 255]. */
  int MaximumHistoryLength = 32;
  /** History shorter than this: variance from a short-history estimate (SVGF 4), [1, 255]. */
  int SpatialVarianceFrames = 4;
  /**
   * The short-history estimate: the photons' own variance where the technique writes
   * it (the squared difference of the estimates of the frame's two halves of photons;
   * vtkCausticsRenderPass::WritesPhotonVariance()) averaged over the history; off, or
   * without it, SVGF's spatial variance of the 7x7 neighbours, which takes a fine
   * caustic's structure for noise and blurs it where the light moves (histories stay
   * short there; docs/denoising.md). Default true.
   */
  bool PhotonVariance = true;
  /** A-trous wavelet iterations (steps 1, 2, 4, ... pixels), [0, 10] (SVGF 5). */
  int AtrousIterations = 5;
  /**
   * The a-trous iteration whose output becomes the colour history, [0, 10]; 0: the
   * temporally integrated colour, unfiltered. SVGF takes 1 (after the first
   * iteration), which feeds the blur back frame after frame: on the ring's sharp
   * nephroid the error against the truth is then 0.91 of the raw estimate's, with 0
   * it is 0.53 (TestSVGFDenoiser, docs/denoising.md). Default 0.
   */
  int HistoryIteration = 0;
  /** Depth edge-stopping: plane distance over this x offset x pixel footprint (SVGF 1). */
  double SigmaDepth = 1.0;
  /** Normal edge-stopping exponent of max(0, n.n') (SVGF 128). */
  double SigmaNormal = 128.0;
  /** Luminance edge-stopping: |dL| over this x the filtered standard deviation (SVGF 4). */
  double SigmaLuminance = 4.0;
  /**
   * History rejection by colour, for light that moves over still receivers (a moving
   * ball's caustic): a reprojected history outside this frame's 5x5 neighbourhood
   * mean +- this many standard deviations (in any channel) is dropped, as a
   * disoccluded one is. 0: off (plain SVGF, which ghosts such light), [0, 100].
   */
  double HistoryRejectionSigmas = 2.0;
  /** Reprojection: a previous surface counts if its plane is within this fraction of
   * the distance to the camera, [1e-5, 1]. */
  double DepthTolerance = 0.01;
  /** Reprojection: and its normal within this cosine, [-1, 1]. */
  double NormalTolerance = 0.9;
  /**
   * Camera cut: when fewer than this fraction of the receiver pixels reproject, the
   * whole history is dropped (as after ResetHistory()), [0, 1].
   */
  double MinimumReprojectedFraction = 0.1;
};
}

#endif
