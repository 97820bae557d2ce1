//! loomkin picking.
