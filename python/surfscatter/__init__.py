"""surfscatter: wave-optical scattering from rough metal surfaces, from numpy.

A thin layer over the C++ library, like the `surfscatter` command-line tool (docs/PYTHON.md):

- materials: Conductor("Au" | path | "perfect") with .ior(lambda_nm) and .reflectance(cos_theta, lambda_nm);
- surface statistics: KCorrelation(sigma, corr_length, gamma), GaussianAcv(sigma, corr_length), TabulatedPsd,
  measured_statistics(height_map) -> MapStatistics; .psd(zeta), .acv(r), .relevant_roughness(theta_i_deg, lambda_nm),
  .self_convolution(max_order), KCorrelation.refit(max_order);
- height maps: HeightMap(heights_um, spacing_um, valid=None), read_height_map, synthesize, fit_surface;
- scattering models: bsdf(model, surface=..., material=..., **options) -> Bsdf with .eval, .pdf, .sample,
  .albedo over numpy arrays, in parallel without the GIL; direction(theta_deg, phi_deg);
- rendering: render(scene, spp=..., params={...}) -> {'rgb', 'xyz', ...} float32 images;
- photographs: read_photo, write_photo, read_camera, Board, calibrate, pose, undistort, colorcorrect, compare.

Units everywhere: wavelengths in nm (lambda_nm), lengths in micrometres (sigma, corr_length, *_um), angles in
degrees (*_deg), spatial frequencies zeta in rad/um; directions are unit vectors (..., 3) in the local frame
(z = surface normal) pointing away from the surface; BRDFs in 1/sr without the cosine (docs/CONVENTIONS.md).
Bad input raises surfscatter.Error (a ValueError) with the library's one-line message.
"""

from ._surfscatter import *  # noqa: F401,F403  (the compiled module defines __all__-worthy names only)
from ._surfscatter import Error, __version__

__all__ = [name for name in dir() if not name.startswith("_")]
