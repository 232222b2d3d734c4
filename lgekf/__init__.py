"""lgekf"""
