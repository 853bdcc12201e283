// src/lib.rs
pub mod pendulum {
    include!(concat!(env!("OUT_DIR"), "/pendulum.rs"));
}
