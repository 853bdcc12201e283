//! Numeric rigid-body helpers for tests of free and spherical joints,
//! written independently of the symbolic engine: the rotation of a unit
//! quaternion, the cross product and a matrix–vector product.

/// The rotation matrix of the unit quaternion `(x, y, z, w)` (vector part
/// first), mapping a body's components to its parent's, in the usual
/// `1 − 2(y² + z²)` form.
pub fn quaternion_rotation([x, y, z, w]: [f64; 4]) -> [[f64; 3]; 3] {
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
        ],
        [
            2.0 * (x * y + w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - w * x),
        ],
        [
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]
}

/// `a × b`.
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `m v`.
#[cfg(any(test, feature = "testing"))]
pub fn mat_vec(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| (0..3).map(|j| m[i][j] * v[j]).sum())
}

/// `mᵀ v`.
#[cfg(any(test, feature = "testing"))]
pub fn transpose_vec(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| (0..3).map(|j| m[j][i] * v[j]).sum())
}
