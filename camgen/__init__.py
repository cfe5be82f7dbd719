"""camgen: disc cams from motion requirements to files you can cut and print."""
__version__ = "0.1.0"
