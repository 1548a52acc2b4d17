"""mechcli: theory of machines (机械原理) from TOML problem files."""

__version__ = "0.1.0"
