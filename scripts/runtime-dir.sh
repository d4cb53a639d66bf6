# Sourced by the other scripts: the Vulkan loader's window-system code (libwayland, which
# lavapipe's loader opens) prints "error: XDG_RUNTIME_DIR is invalid or not set" when the
# variable is unset or names no private directory of this user. Where that is so, point it
# at a fresh private directory (mode 700), removed when the script exits.
xdg_runtime_dir_is_valid() {
    local dir="${XDG_RUNTIME_DIR:-}"
    [ -n "$dir" ] && [ "${dir#/}" != "$dir" ] && [ -d "$dir" ] && [ -O "$dir" ] &&
        [ "$(stat -c %a "$dir")" = 700 ]
}
if ! xdg_runtime_dir_is_valid; then
    XDG_RUNTIME_DIR="$(mktemp -d "${TMPDIR:-/tmp}/runtime-$(id -u)-XXXXXX")"
    chmod 700 "$XDG_RUNTIME_DIR"
    export XDG_RUNTIME_DIR
    trap 'rm -rf "$XDG_RUNTIME_DIR"' EXIT
fi
