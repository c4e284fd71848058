"""Synthetic photographs for the photo suites, made here with numpy (no OpenCV in Python): a chess board seen through
a pinhole camera with OpenCV's lens distortion, and a ColorChecker chart under a colour cast.

The camera is written out independently of the library: a pixel's ray is found by inverting OpenCV's distortion
model (k1 k2 p1 p2) by fixed-point iteration, as cv::undistortPoints does, then intersected with the board's plane.
"""

import numpy as np

# The camera the suites photograph with: 640 x 480, known intrinsics and a barrel distortion.
IMAGE_SIZE = (640, 480)
FX, FY, CX, CY = 600.0, 598.0, 322.5, 236.8
DISTORTION = (-0.12, 0.05, 0.001, -0.0006, 0.0)
SUPERSAMPLE = 3


def look_at(eye, target, up=(0.0, 1.0, 0.0)):
    """World -> OpenCV camera rotation (rows: camera x right, y down, z forward) of a camera at eye."""
    eye, target, up = (np.asarray(v, float) for v in (eye, target, up))
    z = target - eye
    z /= np.linalg.norm(z)
    y = -(up - up.dot(z) * z)
    y /= np.linalg.norm(y)
    return np.stack([np.cross(y, z), y, z])


def pixel_rays():
    """Unit-free camera rays (x, y, 1) of the sub-pixel samples, shape (rows, cols, SUPERSAMPLE^2, 2)."""
    width, height = IMAGE_SIZE
    offsets = (np.arange(SUPERSAMPLE) + 0.5) / SUPERSAMPLE - 0.5  # pixel centres at integer coordinates
    u = np.arange(width)[None, :, None, None] + offsets[None, None, None, :]
    v = np.arange(height)[:, None, None, None] + offsets[None, None, :, None]
    u, v = np.broadcast_arrays(u, v)
    xd = ((u - CX) / FX).reshape(height, width, -1)
    yd = ((v - CY) / FY).reshape(height, width, -1)
    k1, k2, p1, p2, _ = DISTORTION
    x, y = xd.copy(), yd.copy()
    for _ in range(20):  # x_d = x (1 + k1 r^2 + k2 r^4) + 2 p1 x y + p2 (r^2 + 2 x^2), likewise y
        r2 = x * x + y * y
        radial = 1 + k1 * r2 + k2 * r2 * r2
        x = (xd - (2 * p1 * x * y + p2 * (r2 + 2 * x * x))) / radial
        y = (yd - (p1 * (r2 + 2 * y * y) + 2 * p2 * x * y)) / radial
    return np.stack([x, y], axis=-1)


def chessboard_photo(rays, eye, target, squares=(9, 6), square_length_m=0.025):
    """Linear RGB (height, width, 3) of a chess board (squares x, y) centred on the world origin in the plane z = 0,
    a white margin of one square around it, on a grey table; the camera at eye looks at target, world +y up."""
    rotation = look_at(eye, target)
    camera = np.concatenate([rays, np.ones(rays.shape[:-1] + (1,))], axis=-1)
    world = camera @ rotation  # R^T d for every ray
    s = -eye[2] / world[..., 2]
    x = eye[0] + s * world[..., 0]
    y = eye[1] + s * world[..., 1]
    half_w, half_h = squares[0] * square_length_m / 2, squares[1] * square_length_m / 2
    i = np.floor((x + half_w) / square_length_m)
    j = np.floor((y + half_h) / square_length_m)
    on_board = (i >= 0) & (i < squares[0]) & (j >= 0) & (j < squares[1])
    on_margin = (np.abs(x) < half_w + square_length_m) & (np.abs(y) < half_h + square_length_m)
    value = np.where(on_margin, 0.85, 0.25)
    value = np.where(on_board & ((i + j) % 2 == 0), 0.03, value)
    value = np.where(s > 0, value, 0.25)
    grey = value.mean(axis=-1)
    return np.repeat(grey[..., None], 3, axis=-1).astype(np.float32)


def calibration_views():
    """Eye positions that see the board head-on and tilted about 30 degrees in six directions, 0.42 m away."""
    eyes = [np.array([0.0, 0.0, 0.42])]
    for azimuth in np.radians([0, 60, 120, 180, 240, 300]):
        tilt = np.radians(30)
        eyes.append(0.42 * np.array([np.sin(tilt) * np.cos(azimuth), np.sin(tilt) * np.sin(azimuth), np.cos(tilt)]))
    return eyes


# ---- ColorChecker Classic

def reference_linear_srgb(cgats_path):
    """The chart's 24 patches in linear sRGB from the CIELAB (D50) values of an IT8/CGATS file: Lab -> XYZ (D50),
    Bradford adaptation to D65, XYZ -> linear sRGB (IEC 61966-2-1 matrix)."""
    text = open(cgats_path, encoding="ascii", errors="replace").read()
    between = lambda begin, end: text.split(begin + "\n", 1)[1].split(end, 1)[0].split()  # noqa: E731
    fields = between("BEGIN_DATA_FORMAT", "END_DATA_FORMAT")
    values = between("BEGIN_DATA", "END_DATA")
    rows = {values[i]: dict(zip(fields, values[i:i + len(fields)])) for i in range(0, len(values), len(fields))}
    ids = [f"{row}{col:02d}" for row in "ABCD" for col in range(1, 7)]
    lab = np.array([[float(rows[i][k]) for k in ("LAB_L", "LAB_A", "LAB_B")] for i in ids])
    white_d50 = np.array([0.96422, 1.0, 0.82521])
    fy = (lab[:, 0] + 16) / 116
    f = np.stack([fy + lab[:, 1] / 500, fy, fy - lab[:, 2] / 200], axis=1)
    xyz = np.where(f > 6 / 29, f ** 3, 3 * (6 / 29) ** 2 * (f - 4 / 29)) * white_d50
    bradford = np.array([[0.8951, 0.2664, -0.1614], [-0.7502, 1.7135, 0.0367], [0.0389, -0.0685, 1.0296]])
    white_d65 = np.array([0.95047, 1.0, 1.08883])
    scale = (bradford @ white_d65) / (bradford @ white_d50)
    adapted = xyz @ (np.linalg.inv(bradford) @ np.diag(scale) @ bradford).T
    to_srgb = np.array([[3.2404542, -1.5371385, -0.4985314], [-0.9692660, 1.8760108, 0.0415560],
                        [0.0556434, -0.2040259, 1.0572252]])
    return adapted @ to_srgb.T


# A colour cast (a warm light seen by a camera without white balance), applied to the reference.
CAST = np.array([[0.80, 0.10, -0.02], [0.04, 0.62, 0.08], [-0.02, 0.06, 0.45]])
# The chart: patches of PITCH px with GAP px black gaps inside a black frame, its patch grid's top-left at ORIGIN.
PITCH, GAP, FRAME, ORIGIN = 60, 6, 24, (140, 110)


def chart_photo(patches, image_size=(640, 480)):
    """Linear RGB (height, width, 3) of the chart with the given 24 patch colours, axis-aligned, on grey; returns it
    with the patch grid's outer corners (4, 2) in pixels (top-left, top-right, bottom-right, bottom-left) and each
    patch's centre (24, 2)."""
    width, height = image_size
    image = np.full((height, width, 3), 0.18, np.float32)
    x0, y0 = ORIGIN
    image[y0 - FRAME:y0 + 4 * PITCH + FRAME, x0 - FRAME:x0 + 6 * PITCH + FRAME] = 0.03
    centres = []
    for k, colour in enumerate(np.clip(patches, 0, 1)):
        row, col = divmod(k, 6)
        top, left = y0 + row * PITCH, x0 + col * PITCH
        image[top + GAP:top + PITCH - GAP, left + GAP:left + PITCH - GAP] = colour
        centres.append((left + PITCH / 2 - 0.5, top + PITCH / 2 - 0.5))
    # Pixel centres at integers: the grid's outer corners lie on pixel edges, half a pixel before the first pixel.
    corners = np.array([(x0 - 0.5, y0 - 0.5), (x0 + 6 * PITCH - 0.5, y0 - 0.5),
                        (x0 + 6 * PITCH - 0.5, y0 + 4 * PITCH - 0.5), (x0 - 0.5, y0 + 4 * PITCH - 0.5)])
    return image, corners, np.array(centres)
