# Rewrites streamline-kernel module paths and renamed items from before the
# concept folders (issue 19, item 3) to the new ones. See docs/kernel-map.md.
# Run ONCE over code merged from an older branch:
#   sed -i -E -f scripts/kernel_paths.sed $(git ls-files '*.rs')
# (a second run would nest paths again, e.g. sphere::blend::blend::).
# It rewrites only paths written out from `streamline_kernel::` or `crate::`;
# see docs/kernel-map.md for what it cannot do.
#
# --- module moves (order matters: a folder's old module (`streamline::`,
# `sphere::`, `curve::`, `loop_subdiv::`) first, then what moves into it)
s/\b(streamline_kernel|crate)::streamline::/\1::streamline::integrate::/g
s/\b(streamline_kernel|crate)::sphere::/\1::sphere::blend::/g
s/\b(streamline_kernel|crate)::tangent::/\1::sphere::tangent::/g
s/\b(streamline_kernel|crate)::curve::/\1::curve::scheme::/g
s/\b(streamline_kernel|crate)::scalar::/\1::curve::scalar::/g
s/\b(streamline_kernel|crate)::qi::/\1::curve::qi::/g
s/\b(streamline_kernel|crate)::initial_curve::/\1::streamline::initial_curve::/g
s/\b(streamline_kernel|crate)::mesh::/\1::streamline::surface_mesh::/g
s/\b(streamline_kernel|crate)::bspline::/\1::finetune::bspline::/g
s/\b(streamline_kernel|crate)::surface::/\1::levels::surface::/g
s/\b(streamline_kernel|crate)::params::/\1::levels::params::/g
s/\b(streamline_kernel|crate)::incremental::/\1::levels::incremental::/g
s/\b(streamline_kernel|crate)::multires::/\1::levels::multires::/g
s/\b(streamline_kernel|crate)::builder::/\1::levels::builder::/g
s/\b(streamline_kernel|crate)::design::/\1::levels::design::/g
s/\b(streamline_kernel|crate)::presets::/\1::levels::presets::/g
s/\b(streamline_kernel|crate)::window::/\1::levels::dirty_window::/g
s/\b(streamline_kernel|crate)::sphere_pi::/\1::levels::tangent_interpolation::/g
s/\b(streamline_kernel|crate)::loop_subdiv::/\1::loop_subdiv::subdivide::/g
s/\b(streamline_kernel|crate)::trimesh::/\1::loop_subdiv::trimesh::/g
s/\b(streamline_kernel|crate)::interpolate::/\1::loop_subdiv::mesh_interpolation::/g
# `use …::curve::{self, …}` keeps binding the old module name
s/::streamline::integrate::\{self([,}])/::streamline::integrate::{self as streamline\1/g
s/::sphere::blend::\{self([,}])/::sphere::blend::{self as sphere\1/g
s/::curve::scheme::\{self([,}])/::curve::scheme::{self as curve\1/g
s/::loop_subdiv::subdivide::\{self([,}])/::loop_subdiv::subdivide::{self as loop_subdiv\1/g
s/::loop_subdiv::mesh_interpolation::\{self([,}])/::loop_subdiv::mesh_interpolation::{self as interpolate\1/g
s/::levels::tangent_interpolation::\{self([,}])/::levels::tangent_interpolation::{self as sphere_pi\1/g
s/::levels::dirty_window::\{self([,}])/::levels::dirty_window::{self as window\1/g
s/::streamline::surface_mesh::\{self([,}])/::streamline::surface_mesh::{self as mesh\1/g
# a module imported by itself (`use streamline_kernel::interpolate;`) keeps its old name
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate))::streamline;/\1::streamline::integrate as streamline;/
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate))::sphere;/\1::sphere::blend as sphere;/
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate))::curve;/\1::curve::scheme as curve;/
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate))::loop_subdiv;/\1::loop_subdiv::subdivide as loop_subdiv;/
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate))::interpolate;/\1::loop_subdiv::mesh_interpolation as interpolate;/
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate))::sphere_pi;/\1::levels::tangent_interpolation as sphere_pi;/
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate))::window;/\1::levels::dirty_window as window;/
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate))::mesh;/\1::streamline::surface_mesh as mesh;/
# the same paths at the end of a path (doc links, `use …::trimesh;`)
s/\b(streamline_kernel|crate)::trimesh\b([^:]|$)/\1::loop_subdiv::trimesh\2/g
s/\b(streamline_kernel|crate)::interpolate\b([^:]|$)/\1::loop_subdiv::mesh_interpolation\2/g
s/\b(streamline_kernel|crate)::sphere_pi\b([^:]|$)/\1::levels::tangent_interpolation\2/g
s/\b(streamline_kernel|crate)::window\b([^:]|$)/\1::levels::dirty_window\2/g
s/\b(streamline_kernel|crate)::bspline\b([^:]|$)/\1::finetune::bspline\2/g
s/\b(streamline_kernel|crate)::mesh\b([^:]|$)/\1::streamline::surface_mesh\2/g
s/\b(streamline_kernel|crate)::(surface|params|incremental|multires|builder|design|presets)\b([^:]|$)/\1::levels::\2\3/g
s/\b(streamline_kernel|crate)::(initial_curve)\b([^:]|$)/\1::streamline::\2\3/g
s/\b(streamline_kernel|crate)::(scalar|qi)\b([^:]|$)/\1::curve::\2\3/g
s/\b(streamline_kernel|crate)::tangent\b([^:]|$)/\1::sphere::tangent\2/g
# --- modules named inside a one-line `use streamline_kernel::{…}` (or `crate::{…}`):
# the import keeps binding the old name, so code such as `presets::car()` still compiles
:b_streamline
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate)::\{[^}]*[{ ])streamline([,}])/\1streamline::integrate as streamline\5/
t b_streamline
:b_sphere
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate)::\{[^}]*[{ ])sphere([,}])/\1sphere::blend as sphere\5/
t b_sphere
:b_curve
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate)::\{[^}]*[{ ])curve([,}])/\1curve::scheme as curve\5/
t b_curve
:b_loop_subdiv
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate)::\{[^}]*[{ ])loop_subdiv([,}])/\1loop_subdiv::subdivide as loop_subdiv\5/
t b_loop_subdiv
:b_tangent
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate)::\{[^}]*[{ ])tangent([,}])/\1sphere::tangent\5/
t b_tangent
:b_scalar
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate)::\{[^}]*[{ ])scalar([,}])/\1curve::scalar\5/
t b_scalar
:b_qi
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate)::\{[^}]*[{ ])qi([,}])/\1curve::qi\5/
t b_qi
:b_initial_curve
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate)::\{[^}]*[{ ])initial_curve([,}])/\1streamline::initial_curve\5/
t b_initial_curve
:b_mesh
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate)::\{[^}]*[{ ])mesh([,}])/\1streamline::surface_mesh as mesh\5/
t b_mesh
:b_bspline
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate)::\{[^}]*[{ ])bspline([,}])/\1finetune::bspline\5/
t b_bspline
:b_surface
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate)::\{[^}]*[{ ])surface([,}])/\1levels::surface\5/
t b_surface
:b_params
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate)::\{[^}]*[{ ])params([,}])/\1levels::params\5/
t b_params
:b_incremental
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate)::\{[^}]*[{ ])incremental([,}])/\1levels::incremental\5/
t b_incremental
:b_multires
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate)::\{[^}]*[{ ])multires([,}])/\1levels::multires\5/
t b_multires
:b_builder
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate)::\{[^}]*[{ ])builder([,}])/\1levels::builder\5/
t b_builder
:b_design
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate)::\{[^}]*[{ ])design([,}])/\1levels::design\5/
t b_design
:b_presets
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate)::\{[^}]*[{ ])presets([,}])/\1levels::presets\5/
t b_presets
:b_window
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate)::\{[^}]*[{ ])window([,}])/\1levels::dirty_window as window\5/
t b_window
:b_sphere_pi
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate)::\{[^}]*[{ ])sphere_pi([,}])/\1levels::tangent_interpolation as sphere_pi\5/
t b_sphere_pi
:b_trimesh
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate)::\{[^}]*[{ ])trimesh([,}])/\1loop_subdiv::trimesh\5/
t b_trimesh
:b_interpolate
s/^(\s*(pub(\([a-z]+\))? )?use (streamline_kernel|crate)::\{[^}]*[{ ])interpolate([,}])/\1loop_subdiv::mesh_interpolation as interpolate\5/
t b_interpolate
# --- file paths in docs and comments (crates/kernel/src/X.rs)
s#\bcrates/kernel/src/tangent\.rs\b#crates/kernel/src/sphere/tangent.rs#g
s#\bcrates/kernel/src/sphere\.rs\b#crates/kernel/src/sphere/blend.rs#g
s#\bcrates/kernel/src/curve\.rs\b#crates/kernel/src/curve/scheme.rs#g
s#\bcrates/kernel/src/scalar\.rs\b#crates/kernel/src/curve/scalar.rs#g
s#\bcrates/kernel/src/qi\.rs\b#crates/kernel/src/curve/qi.rs#g
s#\bcrates/kernel/src/streamline\.rs\b#crates/kernel/src/streamline/integrate.rs#g
s#\bcrates/kernel/src/initial_curve\.rs\b#crates/kernel/src/streamline/initial_curve.rs#g
s#\bcrates/kernel/src/mesh\.rs\b#crates/kernel/src/streamline/surface_mesh.rs#g
s#\bcrates/kernel/src/bspline\.rs\b#crates/kernel/src/finetune/bspline.rs#g
s#\bcrates/kernel/src/surface\.rs\b#crates/kernel/src/levels/surface.rs#g
s#\bcrates/kernel/src/params\.rs\b#crates/kernel/src/levels/params.rs#g
s#\bcrates/kernel/src/incremental\.rs\b#crates/kernel/src/levels/incremental.rs#g
s#\bcrates/kernel/src/multires\.rs\b#crates/kernel/src/levels/multires.rs#g
s#\bcrates/kernel/src/builder\.rs\b#crates/kernel/src/levels/builder.rs#g
s#\bcrates/kernel/src/design\.rs\b#crates/kernel/src/levels/design.rs#g
s#\bcrates/kernel/src/presets\.rs\b#crates/kernel/src/levels/presets.rs#g
s#\bcrates/kernel/src/window\.rs\b#crates/kernel/src/levels/dirty_window.rs#g
s#\bcrates/kernel/src/sphere_pi\.rs\b#crates/kernel/src/levels/tangent_interpolation.rs#g
s#\bcrates/kernel/src/trimesh\.rs\b#crates/kernel/src/loop_subdiv/trimesh.rs#g
s#\bcrates/kernel/src/loop_subdiv\.rs\b#crates/kernel/src/loop_subdiv/subdivide.rs#g
s#\bcrates/kernel/src/interpolate\.rs\b#crates/kernel/src/loop_subdiv/mesh_interpolation.rs#g
# --- renamed items
# window::Window -> dirty_window::DirtyWindow, on import lines only (Bevy has a `Window`):
# afterwards rename the remaining `Window`s of each file that imports it, e.g.
#   for f in $(git grep -l 'dirty_window::.*DirtyWindow'); do sed -i -E 's/\bWindow\b/DirtyWindow/g' "$f"; done
s/(dirty_window::(\{[^}]*)?)\bWindow\b/\1DirtyWindow/g
