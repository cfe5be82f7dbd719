"""Followers: each turns a motion program into a pitch curve and its contact geometry (see ``base``)."""
