//! loomkin study.
