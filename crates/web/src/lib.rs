//! loomkin web workbench.
