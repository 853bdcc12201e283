//! tmp
#![allow(dead_code)]
mod trig;
